#include "design/optics/working_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"

namespace pinmask {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The paper's optimum-pinhole factor (optics.cpp uses the same for the lensless rule).
constexpr double kOptimumPinholeFactor = 1.56;
// N is clamped here so n * N stays far inside a long long for absurd inputs.
constexpr double kMaxWholePixels = 1e12;

double inverse(double length_m) { return std::isinf(length_m) ? 0.0 : 1.0 / length_m; }

double magnification_at(const Camera& c, double u) {
    return 1.0 - c.sensor_distance_m * inverse(c.lens_focal_m) + c.sensor_distance_m * inverse(u);
}

}  // namespace

void validate(const WorkingDistanceOptions& o) {
    validate_lsi_tolerance(o.lsi_tolerance_px);
    if (o.pixels_per_cell < 0) {
        throw invalid_field("pixels_per_cell", std::to_string(o.pixels_per_cell),
                            "must be >= 1 (or 0: the nearest whole number at u)");
    }
}

void check_object_distance(const Camera& c, double u, const char* field) {
    if (std::isnan(u) || !(u > 0.0)) {
        throw invalid_field(field, std::isnan(u) ? "nan" : format_length(u),
                            "must be > 0 (inf allowed)");
    }
    if (std::isfinite(c.lens_focal_m) && u <= c.lens_focal_m) {
        throw invalid_field(field, format_length(u),
                            "is inside the focal length f' = " + format_length(c.lens_focal_m) +
                                " of the lens: the thin lens forms no real image of such an "
                                "object; use an object distance beyond f'");
    }
}

double pixels_per_cell_at(const Camera& c, double u) {
    return std::fabs(magnification_at(c, u)) * c.pinhole_m / c.pixel_pitch_m;
}

std::optional<std::string> sub_pixel_cells(const Camera& c) {
    const auto format_number = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3g", v);
        return std::string(buf);
    };
    const double pitch = pixels_per_cell_at(c, c.object_distance_m);
    if (!(pitch > 0.0 && pitch < 0.5)) return std::nullopt;
    return "one cell (pinhole_m " + format_length(c.pinhole_m) + " times |1 - f/f' + f/u| = " +
           format_number(std::fabs(magnification_at(c, c.object_distance_m))) + ") images to " +
           format_number(pitch) + " px of pixel_pitch_m " + format_length(c.pixel_pitch_m) +
           " at u = " + format_length(c.object_distance_m) +
           ": less than half a pixel, so the pattern is not resolved and the whole-pixel "
           "models use 1 px per cell, not this camera; check lens_focal_m, sensor_distance_m, "
           "pinhole_m and pixel_pitch_m";
}

double pinhole_for_pixels_per_cell(const Camera& c, long long n_px) {
    if (n_px < 1) {
        throw invalid_field("pixels_per_cell", std::to_string(n_px), "must be >= 1");
    }
    const double m = magnification_at(c, c.object_distance_m);
    if (m == 0.0) {
        throw invalid_field(
            "pixels_per_cell", std::to_string(n_px),
            "cannot be reached: 1 - f/f' + f/u = 0 (f = f' = " +
                format_length(c.sensor_distance_m) +
                " with u = inf: z_eff is infinite, the Fraunhofer limit) so every pinhole images "
                "to the same spot whatever its size; give a finite object distance or f != f'");
    }
    return static_cast<double>(n_px) * c.pixel_pitch_m / std::fabs(m);
}

Mask mask_at_distance(const Mask& mask, double u) {
    validate(mask.camera);
    check_object_distance(mask.camera, u, "object_distance_m");
    Mask out = mask;
    out.camera.object_distance_m = u;
    const double pitch = pixels_per_cell_at(out.camera, u);
    out.psf.pixels_per_cell = static_cast<int>(std::clamp(std::round(pitch), 1.0, 65536.0));
    return out;
}

RefocusGeometry refocus_geometry(const Mask& mask, double u) {
    validate(mask.camera);
    check_object_distance(mask.camera, u, "object_distance_m");
    RefocusGeometry g;
    g.pitch_px = pixels_per_cell_at(mask.camera, u);
    g.whole_px = static_cast<long long>(std::clamp(std::round(g.pitch_px), 1.0, 65536.0));
    g.mismatch_px = mask.pattern.n * std::fabs(g.pitch_px - static_cast<double>(g.whole_px));
    g.exact_geometry = g.mismatch_px > kRefocusWholeTolerancePx;
    return g;
}

WorkingDistance compute_working_distance(const Camera& c, const PatternGeometry& g,
                                         const WorkingDistanceOptions& o) {
    validate(c);
    validate(g);
    validate(o);
    check_object_distance(c, c.object_distance_m);
    WorkingDistance r;
    const double u = c.object_distance_m, f = c.sensor_distance_m, w = c.pixel_pitch_m;
    const double d = c.pinhole_m, lambda = c.wavelength_m;
    r.object_distance_m = u;
    r.pixels_per_cell_at_u = pixels_per_cell_at(c, u);
    r.pixels_per_cell =
        o.pixels_per_cell > 0
            ? o.pixels_per_cell
            : static_cast<long long>(
                  std::min(std::max(1.0, std::round(r.pixels_per_cell_at_u)), kMaxWholePixels));
    r.pinhole_for_pixels_per_cell_m =
        magnification_at(c, u) == 0.0 ? kInf : pinhole_for_pixels_per_cell(c, r.pixels_per_cell);
    r.period_px = g.n * r.pixels_per_cell_at_u;
    r.lsi_mismatch_px =
        g.n * std::fabs(r.pixels_per_cell_at_u - static_cast<double>(r.pixels_per_cell));
    r.lsi_tolerance_px = o.lsi_tolerance_px;
    r.psf_size_px = static_cast<long long>(g.n) * r.pixels_per_cell;
    r.periods_on_sensor_cols = c.sensor_cols / static_cast<double>(r.psf_size_px);
    r.periods_on_sensor_rows = c.sensor_rows / static_cast<double>(r.psf_size_px);

    // f s_max |1/u' - 1/u| / w <= t  <=>  |1/u' - 1/u| <= t w / (f n d).
    const double dx = o.lsi_tolerance_px * w / (f * g.n * d);
    const double x0 = inverse(u);
    const double x_far = x0 - dx, x_near = x0 + dx;
    r.range_far_m = x_far <= 0.0 ? kInf : 1.0 / x_far;
    r.range_near_m = 1.0 / x_near;
    if (std::isfinite(c.lens_focal_m) && r.range_near_m < c.lens_focal_m) {
        r.range_near_m = c.lens_focal_m;
        r.range_near_clamped_to_focal = true;
    }

    const double inv_z = 1.0 / f - inverse(c.lens_focal_m) + x0;
    r.optimum_pinhole_lensless_m = kOptimumPinholeFactor * std::sqrt(lambda * f);
    r.optimum_pinhole_with_lens_m =
        inv_z == 0.0 ? kInf : kOptimumPinholeFactor * std::sqrt(lambda / std::fabs(inv_z));
    r.fresnel_number_with_lens_at_u = d * d * std::fabs(inv_z) / (4.0 * lambda);
    r.spot_spread_cells = r.fresnel_number_with_lens_at_u == 0.0
                              ? kInf
                              : std::max(1.0, 1.0 / (2.0 * r.fresnel_number_with_lens_at_u));
    return r;
}

}  // namespace pinmask
