#include "design/optics/camera.hpp"

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"

namespace pinmask {
namespace {

// Finite lengths outside [1 fm, 1000 km] describe no camera, and their products in the optics
// (d^2 / (4 lambda f), f s / u) overflow or underflow a double: refused, with the reason.
constexpr double kMinLength_m = 1e-15;
constexpr double kMaxLength_m = 1e6;

void require_positive(const char* field, double v, bool allow_inf) {
    if (std::isnan(v) || v <= 0.0 || (!allow_inf && std::isinf(v))) {
        throw invalid_field(field, std::isnan(v) ? "nan" : format_length(v),
                            allow_inf ? "must be > 0 (inf allowed)" : "must be finite and > 0");
    }
    if (std::isfinite(v) && (v < kMinLength_m || v > kMaxLength_m)) {
        throw invalid_field(field, format_length(v),
                            "must be between 1e-15 m and 1e6 m (1000 km)" +
                                std::string(allow_inf ? " or inf" : "") +
                                ": no camera has such a length, and the optics' products of "
                                "lengths would overflow or underflow");
    }
}

}  // namespace

Camera paper_camera() { return Camera{}; }

void validate(const Camera& c) {
    require_positive("object_distance_m", c.object_distance_m, true);
    require_positive("lens_focal_m", c.lens_focal_m, true);
    require_positive("sensor_distance_m", c.sensor_distance_m, false);
    require_positive("wavelength_m", c.wavelength_m, false);
    // 0 is one wavelength; a Gaussian band sampled over +-1.5 FWHM (design/optics/spectrum) stays
    // at wavelengths >= lambda / 4 up to B = lambda / 2, and no light source a mask is designed for
    // is broader than that around its centre.
    if (!(c.bandwidth_m >= 0.0) || !(c.bandwidth_m <= 0.5 * c.wavelength_m)) {
        throw invalid_field(
            "bandwidth_m", std::isnan(c.bandwidth_m) ? "nan" : format_length(c.bandwidth_m),
            "must be >= 0 and at most half the wavelength (" + format_length(0.5 * c.wavelength_m) +
                "): the full width at half maximum of the light's spectrum, 0 "
                "for one wavelength");
    }
    require_positive("pixel_pitch_m", c.pixel_pitch_m, false);
    require_positive("pinhole_m", c.pinhole_m, false);
    // One rule for every command that builds a camera (design, generate, psf, search, ...): the
    // object must be beyond a finite lens's focal length, else the lens forms no real image and
    // the mask written would be one no other command accepts.
    if (std::isfinite(c.lens_focal_m) && c.object_distance_m <= c.lens_focal_m) {
        throw invalid_field("object_distance_m", format_length(c.object_distance_m),
                            "is inside the focal length f' = " + format_length(c.lens_focal_m) +
                                " of the lens: the thin lens forms no real image of such an "
                                "object; use an object distance beyond f'");
    }
    if (c.sensor_cols < 1 || c.sensor_rows < 1) {
        throw invalid_field("sensor",
                            std::to_string(c.sensor_cols) + "x" + std::to_string(c.sensor_rows),
                            "width and height must be >= 1");
    }
}

}  // namespace pinmask
