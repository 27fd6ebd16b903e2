#include "design/optics/camera.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

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

// The largest value each length can have in a camera this project designs for, with the unit
// it is usually written in. A larger value is almost always a number typed without its unit
// (a plain number is metres: `--pinhole 300` is a 300 m pinhole), so it is refused with the
// unit that puts it in range. Object distances have no cap (a distant object is legal).
struct LengthCap {
    const char* field;
    double max_m;
    double min_m;      // the smallest real one: a suggested unit must land between the two
    const char* what;  // "a pinhole": what no real one exceeds
    // Units tried in order for the suggestion, the quantity's usual unit first (nullptr: none).
    const char* units[3];
};

constexpr LengthCap kLengthCaps[] = {
    {"pinhole_m", 10e-3, 1e-6, "a pinhole side", {"um", "mm", "nm"}},
    {"pixel_pitch_m", 1e-3, 1e-7, "a sensor pixel pitch", {"um", "nm", nullptr}},
    {"wavelength_m", 100e-6, 10e-9, "a design wavelength", {"nm", "um", nullptr}},
    {"sensor_distance_m", 10.0, 10e-6, "a lens-to-sensor distance", {"mm", "cm", nullptr}},
    {"lens_focal_m", 10.0, 100e-6, "a lens focal length", {"mm", "cm", nullptr}},
};

double unit_factor(std::string_view unit) {
    if (unit == "mm") return 1e-3;
    if (unit == "cm") return 1e-2;
    if (unit == "um") return 1e-6;
    return 1e-9;  // nm
}

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// Significant digits of v as %.6g prints it, leading and trailing zeros aside: 300 -> 1,
// 0.44 -> 2, 0.0149461 -> 6.
int significant_digits(double v) {
    std::string digits;
    for (const char c : number_text(v)) {
        if (c == 'e') break;
        if (c >= '0' && c <= '9') digits += c;
    }
    const auto first = digits.find_first_not_of('0');
    if (first == std::string::npos) return 0;
    const auto last = digits.find_last_not_of('0');
    return static_cast<int>(last - first + 1);
}

// Refuses a finite length above its quantity's cap. A number typed by hand (at most four
// significant digits, not a computed value) gets the unit it probably meant: the first of the
// quantity's units that puts the same number between its smallest and largest real values.
void require_plausible(const LengthCap& cap, double v) {
    if (!std::isfinite(v) || v <= cap.max_m) return;
    std::string rule = "larger than " + std::string(cap.what) + " can be (at most " +
                       format_length(cap.max_m) + "); a number without a unit is in metres";
    std::string hint = ": give the length with its unit (e.g. 440um, 55mm, 550nm)";
    for (const char* unit : cap.units) {
        if (!unit || significant_digits(v) > 4) break;
        const double scaled = v * unit_factor(unit);
        if (scaled <= cap.max_m && scaled >= cap.min_m) {
            hint = ": did you mean " + number_text(v) + unit + "?";
            break;
        }
    }
    throw invalid_field(cap.field, format_length(v), rule + hint);
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
    const auto value_of = [&c](std::string_view field) {
        if (field == "pinhole_m") return c.pinhole_m;
        if (field == "pixel_pitch_m") return c.pixel_pitch_m;
        if (field == "wavelength_m") return c.wavelength_m;
        if (field == "sensor_distance_m") return c.sensor_distance_m;
        return c.lens_focal_m;
    };
    for (const LengthCap& cap : kLengthCaps) require_plausible(cap, value_of(cap.field));
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
