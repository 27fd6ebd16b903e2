#include "optimize/metrics/depth_fisher.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/psf_exact.hpp"

namespace pinmask {
namespace {
// FWHM of a Gaussian in units of its standard deviation: 2 sqrt(2 ln 2).
constexpr double kFwhmPerSigma = 2.3548200450309493;
}  // namespace

void DepthFisherOptions::validate() const {
    if (!(photons > 0.0) || !std::isfinite(photons)) {
        throw invalid_field(field_ref("photons"), std::to_string(photons),
                            "must be finite and > 0");
    }
    if (!(read_noise_e >= 0.0) || !std::isfinite(read_noise_e)) {
        throw invalid_field(field_ref("read_noise"), std::to_string(read_noise_e),
                            "must be finite and >= 0");
    }
    if (rows < 0 || cols < 0) {
        throw invalid_field("size", std::to_string(rows) + "x" + std::to_string(cols),
                            "must be >= 0 (0: the sensor)");
    }
}

DepthSlope depth_slope(const Mask& mask, double u, int rows, int cols) {
    if (!std::isfinite(u)) {
        throw invalid_field(field_ref("object_distance_m"), format_length(u),
                            "must be finite (the bound is in 1/u around u)");
    }
    check_object_distance(mask.camera, u, "object_distance_m");
    const Camera& c = mask.camera;
    const double nt_d = static_cast<double>(mask.pattern.n) *
                        std::max(mask.pattern.tiles_rows, mask.pattern.tiles_cols) * c.pinhole_m;
    DepthSlope out;
    out.object_distance_m = u;
    out.one_pixel_inverse_per_m = c.pixel_pitch_m / (c.sensor_distance_m * nt_d);
    const double t = 1.0 / u, dt = out.one_pixel_inverse_per_m / 20.0;
    // Stay on the object side of the lens: t + dt must keep u > f'.
    if (std::isfinite(c.lens_focal_m) && !(t + dt < 1.0 / c.lens_focal_m)) {
        throw invalid_field(field_ref("object_distance_m"), format_length(u),
                            "is too close to the focal length for the difference step");
    }
    ExactPsfOptions eo;
    eo.rows = rows;
    eo.cols = cols;
    eo.object_distance_m = u;
    out.psf = exact_psf(mask, eo);
    eo.object_distance_m = 1.0 / (t + dt);
    const Plane hp = exact_psf(mask, eo);
    const Plane hm =
        t > dt ? (eo.object_distance_m = 1.0 / (t - dt), exact_psf(mask, eo)) : out.psf;
    const double step = t > dt ? 2.0 * dt : dt;
    out.slope = (hp - hm) / step;
    return out;
}

DepthFisher depth_fisher(const DepthSlope& s, const DepthFisherOptions& o) {
    o.validate();
    DepthFisher out;
    out.object_distance_m = s.object_distance_m;
    out.one_pixel_inverse_per_m = s.one_pixel_inverse_per_m;
    const double r2 = o.read_noise_e * o.read_noise_e;
    double info = 0.0;
    for (Eigen::Index i = 0; i < s.psf.size(); ++i) {
        const double var = o.photons * s.psf.data()[i] + r2;
        const double d = o.photons * s.slope.data()[i];
        if (var > 0.0) info += d * d / var;
    }
    const double u = s.object_distance_m;
    out.fisher_inverse_m2 = info;
    out.crb_inverse_per_m = info > 0.0 ? 1.0 / std::sqrt(info) : INFINITY;
    out.crb_distance_m = u * u * out.crb_inverse_per_m;
    return out;
}

DepthFisher depth_fisher(const Mask& mask, double u, const DepthFisherOptions& o) {
    o.validate();
    return depth_fisher(depth_slope(mask, u, o.rows, o.cols), o);
}

DepthFisherOptions depth_fisher_noise(const NoiseModel& model, int open_cells) {
    if (model.kind != NoiseKind::kPhoton) {
        const std::string photons = field_ref("photons");
        throw InvalidInput(
            "the depth figure (a Cramer-Rao bound under photon noise) needs the "
            "photon model (" +
            photons + "), not Gaussian noise at an SNR");
    }
    DepthFisherOptions o;
    o.photons = model.photons_per_pinhole * open_cells;
    double var = model.read_noise_e * model.read_noise_e + model.dark_current_e;
    if (model.adc_bits > 0 && std::isfinite(model.full_well_e)) {
        const double q = model.full_well_e / (std::ldexp(1.0, model.adc_bits) - 1.0);
        var += q * q / 12.0;
    }
    o.read_noise_e = std::sqrt(var);
    return o;
}

void DepthRange::validate() const {
    const bool given = from_m != 0.0 || to_m != 0.0;
    for (const auto& [v, name] :
         {std::pair{from_m, "depth_from_m"}, std::pair{to_m, "depth_to_m"}}) {
        if (given && (!(v > 0.0) || !std::isfinite(v))) {
            throw invalid_field(field_ref(name), std::isnan(v) ? "nan" : format_length(v),
                                "must be finite and > 0 (give both ends, or neither for the "
                                "working distance / 2 .. x 2)");
        }
    }
    if (given && !(from_m <= to_m)) {
        throw invalid_field(
            field_ref("depth_to_m"), format_length(to_m),
            "must be >= " + field_ref("depth_from_m") + " = " + format_length(from_m));
    }
    if (samples < 1 || samples > 64)
        throw invalid_field("samples", std::to_string(samples), "must be in 1 .. 64");
}

std::vector<double> depth_samples(const Mask& mask, const DepthRange& range) {
    range.validate();
    double from = range.from_m, to = range.to_m;
    if (from == 0.0 && to == 0.0) {
        const double uw = mask.camera.object_distance_m;
        if (!std::isfinite(uw)) {
            throw invalid_field(field_ref("depth_from_m"), "(not given)",
                                "is needed for a mask designed for an infinite working distance "
                                "(the default range is u / 2 .. 2 u)");
        }
        from = uw / 2.0;
        to = 2.0 * uw;
    }
    const double focal = mask.camera.lens_focal_m;
    if (std::isfinite(focal) && !(from > focal * (1.0 + 1e-9))) {
        throw invalid_field(field_ref("depth_from_m"), format_length(from),
                            "must be beyond the lens focal length f' = " + format_length(focal) +
                                " (the thin lens forms no real image nearer)");
    }
    std::vector<double> u;
    const int k = from == to ? 1 : range.samples;
    for (int i = 0; i < k; ++i) {
        const double a = k == 1 ? 0.0 : static_cast<double>(i) / (k - 1);
        u.push_back(i == 0 ? from : i == k - 1 ? to : 1.0 / ((1.0 - a) / from + a / to));
    }
    return u;
}

DepthFigures depth_figures(const std::vector<DepthSlope>& slopes, const DepthFisherOptions& o) {
    if (slopes.empty()) throw InvalidInput("depth_figures: no distances");
    DepthFigures f;
    f.from_m = slopes.front().object_distance_m;
    f.to_m = slopes.back().object_distance_m;
    f.crb_rel = -1.0;
    for (const DepthSlope& s : slopes) {
        const DepthFisher b = depth_fisher(s, o);
        const double rel = b.crb_distance_m / s.object_distance_m;
        if (rel > f.crb_rel) {
            f.crb_rel = rel;
            f.worst_distance_m = s.object_distance_m;
        }
        f.axial_fwhm_m = std::max(f.axial_fwhm_m, kFwhmPerSigma * b.crb_distance_m);
    }
    return f;
}

}  // namespace pinmask
