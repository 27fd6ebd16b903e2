#include "design/optics/optics.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"

namespace pinmask {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// d_opt = 1.56 sqrt(lambda f): the optimum single-pinhole side quoted by the paper.
constexpr double kOptimumPinholeFactor = 1.56;
// n_px is clamped here so n * n_px stays far inside a long long for absurd inputs.
constexpr double kMaxPixelsPerCell = 1e12;

double inverse(double length_m) { return std::isinf(length_m) ? 0.0 : 1.0 / length_m; }

// 1/x with 1/0 = +inf (an infinite distance), keeping the sign otherwise.
double distance_from_inverse(double inv) { return inv == 0.0 ? kInf : 1.0 / inv; }

}  // namespace

PatternGeometry geometry_of(const Pattern& p) {
    return {p.n, static_cast<int>(p.pinholes.size()), p.tiles_rows, p.tiles_cols};
}

void validate(const PatternGeometry& g) {
    if (g.n < 1 || g.n > kMaxGrid) {
        throw invalid_field(field_ref("grid"), std::to_string(g.n),
                            "must be between 1 and " + std::to_string(kMaxGrid));
    }
    const long long cells = static_cast<long long>(g.n) * g.n;
    if (g.holes < 0 || g.holes > cells) {
        throw invalid_field(field_ref("holes"), std::to_string(g.holes),
                            "must be between 0 and n^2 = " + std::to_string(cells));
    }
    if (g.tiles_rows < 1 || g.tiles_cols < 1 || g.tiles_rows > kMaxTiles ||
        g.tiles_cols > kMaxTiles) {
        throw invalid_field(field_ref("tiles"),
                            g.tiles_rows == g.tiles_cols
                                ? std::to_string(g.tiles_rows)
                                : std::to_string(g.tiles_rows) + "x" + std::to_string(g.tiles_cols),
                            "must be between 1 and " + std::to_string(kMaxTiles) +
                                " per side (as a mask file's pattern.tiles)");
    }
}

double inverse_effective_distance_at_u(const Camera& c) {
    return 1.0 / c.sensor_distance_m - inverse(c.lens_focal_m) + inverse(c.object_distance_m);
}

double magnification_at_u(const Camera& c) {
    return c.sensor_distance_m * inverse_effective_distance_at_u(c);
}

double design_pixels_per_cell(const Camera& c) {
    const double magnification =
        c.sensor_distance_m * (1.0 / c.sensor_distance_m - inverse(c.lens_focal_m));
    return std::fabs(magnification) * c.pinhole_m / c.pixel_pitch_m;
}

double fresnel_number_at_u(const Camera& c) {
    return c.pinhole_m * c.pinhole_m * std::fabs(inverse_effective_distance_at_u(c)) /
           (4.0 * c.wavelength_m);
}

void validate_lsi_tolerance(double t_px) {
    if (!(t_px >= kMinLsiTolerancePx) || !(t_px <= kMaxLsiTolerancePx)) {
        char value[32];
        std::snprintf(value, sizeof value, "%g", t_px);
        throw invalid_field(field_ref("lsi_tolerance_px"), value,
                            "must be between 1e-6 and 1000 px (0 or less gives an empty "
                            "object-distance range, a millionth of a pixel is below what any "
                            "sensor or PSF model resolves, and a mismatch of more than a whole "
                            "period of any real sensor says nothing)");
    }
}

OpticsReport compute_optics(const Camera& c, const PatternGeometry& g, KernelModel requested,
                            const OpticsOptions& options) {
    validate(c);
    validate(g);
    validate_lsi_tolerance(options.lsi_tolerance_px);
    OpticsReport r;
    r.camera = c;
    r.geometry = g;
    r.options = options;
    const double f = c.sensor_distance_m, d = c.pinhole_m, w = c.pixel_pitch_m;
    const double lambda = c.wavelength_m;

    const double inv_z = 1.0 / f - inverse(c.lens_focal_m);
    const double inv_z_u = inverse_effective_distance_at_u(c);
    r.magnification = f * inv_z;
    r.magnification_at_u = f * inv_z_u;
    r.geometric_spot_m = std::fabs(r.magnification) * d;
    r.geometric_spot_at_u_m = std::fabs(r.magnification_at_u) * d;
    r.pixels_per_cell_at_inf = design_pixels_per_cell(c);
    r.pixels_per_cell_at_u = r.geometric_spot_at_u_m / w;
    const double rounded = std::max(1.0, std::round(r.pixels_per_cell_at_inf));
    r.integer_pixels_per_cell = static_cast<long long>(std::min(rounded, kMaxPixelsPerCell));
    r.pinhole_for_integer_pixels_m =
        r.magnification == 0.0 ? kInf : rounded * w / std::fabs(r.magnification);

    r.optimum_pinhole_m = kOptimumPinholeFactor * std::sqrt(lambda * f);
    r.fresnel_number = d * d / (4.0 * lambda * f);
    r.effective_distance_m = distance_from_inverse(inv_z);
    r.effective_distance_at_u_m = distance_from_inverse(inv_z_u);
    r.fresnel_number_with_lens = d * d * std::fabs(inv_z) / (4.0 * lambda);
    r.fresnel_number_with_lens_at_u = fresnel_number_at_u(c);

    r.max_separation_m = g.n * d;
    r.lsi_min_object_distance_m = f * r.max_separation_m / (options.lsi_tolerance_px * w);
    r.lsi_mismatch_px = f * r.max_separation_m * inverse(c.object_distance_m) / w;

    r.psf_size_px = static_cast<long long>(g.n) * r.integer_pixels_per_cell;
    r.periods_on_sensor_cols = c.sensor_cols / static_cast<double>(r.psf_size_px);
    r.periods_on_sensor_rows = c.sensor_rows / static_cast<double>(r.psf_size_px);
    r.mask_width_m = static_cast<double>(g.n) * g.tiles_cols * d;
    r.mask_height_m = static_cast<double>(g.n) * g.tiles_rows * d;
    r.open_fraction = g.holes / (static_cast<double>(g.n) * g.n);
    r.light_gain = g.holes;

    if (requested == KernelModel::kAuto) {
        const KernelChoice choice = choose_kernel_model(r.fresnel_number_with_lens_at_u);
        r.kernel_model = choice.model;
        r.kernel_reason = "auto: " + choice.reason;
    } else {
        r.kernel_model = requested;
        r.kernel_reason = requested == KernelModel::kPaperFig3b
                              ? "requested: the paper's measured Fig. 3b table (8 px per cell)"
                              : "requested";
    }
    return r;
}

}  // namespace pinmask
