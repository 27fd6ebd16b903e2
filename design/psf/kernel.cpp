#include "design/psf/kernel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/image/image_io.hpp"
#include "core/units/units.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/spectrum.hpp"
#include "design/psf/kernel_profile.hpp"
#include "design/psf/paper_kernel.hpp"

namespace pinmask {
namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

Camera at_wavelength(const Camera& c, double wavelength_m) {
    Camera out = c;
    out.wavelength_m = wavelength_m;
    return out;
}

PixelProfile profile_for(const Camera& c, KernelModel model, int ppc, const KernelOptions& o) {
    switch (model) {
        case KernelModel::kBox:
            return box_pixel_profile(
                std::fabs(magnification_at_u(c)) * c.pinhole_m / c.pixel_pitch_m, ppc, o);
        case KernelModel::kFraunhofer: {
            const double pixel_v =
                c.pinhole_m * c.pixel_pitch_m / (c.wavelength_m * c.sensor_distance_m);
            return diffraction_pixel_profile(fraunhofer_profile, pixel_v, ppc, o);
        }
        case KernelModel::kFresnel: {
            const double pixel_v =
                c.pinhole_m * c.pixel_pitch_m / (c.wavelength_m * c.sensor_distance_m);
            const FresnelProfile h(fresnel_number_at_u(c));
            return diffraction_pixel_profile([&h](double v) { return h(v); }, pixel_v, ppc, o);
        }
        default:
            throw InvalidInput("kernel model " + kernel_model_name(model) +
                               " has no optical profile");
    }
}

// Weighted (weights sum 1) sum of the normalised separable kernels p(r) p(c), one profile per
// wavelength, on their common symmetric support.
Kernel merge(const std::vector<PixelProfile>& monos,
             const std::vector<std::pair<double, double>>& wl) {
    int origin = monos[0].origin;
    int end = origin + static_cast<int>(monos[0].values.size());
    for (const PixelProfile& m : monos) {
        origin = std::min(origin, m.origin);
        end = std::max(end, m.origin + static_cast<int>(m.values.size()));
    }
    Kernel k;
    k.values = Plane::Zero(end - origin, end - origin);
    k.origin_row = k.origin_col = origin;
    k.enclosed_energy = 0.0;
    for (std::size_t i = 0; i < monos.size(); ++i) {
        const PixelProfile& p = monos[i];
        double sum = 0.0;
        for (double v : p.values) sum += v;
        const int off = p.origin - origin;
        const double weight = wl[i].second / (sum * sum);
        for (std::size_t r = 0; r < p.values.size(); ++r) {
            for (std::size_t c = 0; c < p.values.size(); ++c) {
                k.values(off + static_cast<int>(r), off + static_cast<int>(c)) +=
                    weight * (p.values[r] * p.values[c]);
            }
        }
        k.enclosed_energy += wl[i].second * p.enclosed * p.enclosed;
        k.support_capped = k.support_capped || p.capped;
    }
    k.values /= k.values.sum();  // removes the last rounding of the weights
    k.wavelengths = wl;
    return k;
}

std::vector<std::pair<double, double>> normalised_wavelengths(const Camera& c,
                                                              const KernelSpec& spec) {
    if (spec.wavelengths.empty()) return band_wavelengths(c);
    // One source of the spectrum: an explicit list beside a camera band would leave the user
    // guessing which one the kernel used.
    if (c.bandwidth_m > 0.0) {
        throw invalid_field(field_ref("bandwidth_m"), format_length(c.bandwidth_m),
                            "and the mask's psf.kernel.wavelengths both give the spectrum: "
                            "give one of them (bandwidth 0, or no wavelength list)");
    }
    double total = 0.0;
    for (std::size_t i = 0; i < spec.wavelengths.size(); ++i) {
        const auto [lambda, weight] = spec.wavelengths[i];
        const std::string field = "kernel wavelengths[" + std::to_string(i) + "]";
        if (!(lambda > 0.0) || std::isinf(lambda)) {
            throw invalid_field(field + " wavelength_m", number(lambda), "must be finite and > 0");
        }
        if (!(weight >= 0.0) || std::isinf(weight)) {
            throw invalid_field(field + " weight", number(weight), "must be finite and >= 0");
        }
        total += weight;
    }
    if (!(total > 0.0))
        throw invalid_field("kernel wavelengths", "all weights 0", "need a sum > 0");
    std::vector<std::pair<double, double>> out;
    for (const auto& [lambda, weight] : spec.wavelengths) {
        if (weight > 0.0) out.emplace_back(lambda, weight / total);
    }
    return out;
}

}  // namespace

Kernel measured_kernel(const Plane& values, int ppc, const std::string& source) {
    if (ppc < 1 || ppc > kMaxPixelsPerCell) {
        throw invalid_field("pixels_per_cell", std::to_string(ppc),
                            "must be between 1 and " + std::to_string(kMaxPixelsPerCell));
    }
    if (values.size() == 0) throw invalid_field("measured kernel " + source, "empty", "no pixels");
    if (!is_all_finite(values)) {
        throw invalid_field("measured kernel " + source, "NaN or Inf", "values must be finite");
    }
    const double sum = values.sum();
    if (!(sum > 0.0)) {
        throw invalid_field("measured kernel " + source, "sum " + number(sum),
                            "must be > 0 (all zeros or negative)");
    }
    Kernel k;
    k.values = values / sum;
    k.origin_row = ppc / 2 - static_cast<int>(values.rows() / 2);
    k.origin_col = ppc / 2 - static_cast<int>(values.cols() / 2);
    k.model = KernelModel::kMeasured;
    k.model_reason = "requested";
    k.source = source;
    return k;
}

Kernel make_kernel(const Camera& camera, const KernelSpec& spec, int ppc,
                   const KernelOptions& options) {
    validate(camera);
    validate(options);
    if (ppc < 1 || ppc > kMaxPixelsPerCell) {
        throw invalid_field("pixels_per_cell", std::to_string(ppc),
                            "must be between 1 and " + std::to_string(kMaxPixelsPerCell));
    }
    const KernelModel requested = parse_kernel_model(spec.model, "kernel model");
    if (requested == KernelModel::kPaperFig3b) {
        if (ppc != kPaperKernelSide) {
            throw invalid_field("pixels_per_cell", std::to_string(ppc),
                                "the paper-fig3b kernel is the paper's 8 x 8 table, defined only "
                                "for 8 pixels per cell (set pixels per cell to 8)");
        }
        Kernel k;
        k.values = paper_fig3b_kernel();
        k.origin_row = k.origin_col = 0;  // the table covers the cell; centre at ppc/2 = 4
        k.model = KernelModel::kPaperFig3b;
        k.model_reason = "requested: the paper's measured Fig. 3b table";
        k.wavelengths = {{camera.wavelength_m, 1.0}};
        k.source = "paper Fig. 3b";
        return k;
    }
    if (requested == KernelModel::kMeasured) {
        if (spec.measured_path.empty()) {
            throw invalid_field("kernel measured_path", "''", "model 'measured' needs a file");
        }
        const LoadedImage img = read_image(spec.measured_path);
        if (img.image.n_channels() != 1) {
            throw invalid_field("measured kernel " + spec.measured_path,
                                std::to_string(img.image.n_channels()) + " channels",
                                "must be a single-channel (grey) image");
        }
        return measured_kernel(img.image.channels[0], ppc, spec.measured_path);
    }
    const auto wavelengths = normalised_wavelengths(camera, spec);
    KernelChoice chosen{requested, "requested"};
    if (requested == KernelModel::kAuto) {
        chosen =
            choose_kernel_model(fresnel_number_at_u(at_wavelength(camera, wavelengths[0].first)));
        chosen.reason = "auto: " + chosen.reason;
        for (std::size_t i = 1; i < wavelengths.size(); ++i) {
            const KernelChoice other = choose_kernel_model(
                fresnel_number_at_u(at_wavelength(camera, wavelengths[i].first)));
            if (other.model != chosen.model) {
                chosen = {KernelModel::kFresnel,
                          "auto: the wavelengths fall in different regimes, fresnel for all"};
                break;
            }
        }
        if (wavelengths.size() > 1 &&
            chosen.reason.find("different regimes") == std::string::npos) {
            chosen.reason += " (N at the first wavelength, " + format_length(wavelengths[0].first) +
                             "; the same model at every other wavelength)";
        }
    }
    std::vector<PixelProfile> monos;
    for (const auto& wl : wavelengths) {
        monos.push_back(profile_for(at_wavelength(camera, wl.first), chosen.model, ppc, options));
    }
    Kernel k = merge(monos, wavelengths);
    k.model = chosen.model;
    k.model_reason = chosen.reason;
    return k;
}

}  // namespace pinmask
