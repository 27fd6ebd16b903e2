#include "design/camera.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/units.hpp"

namespace pinmask {
namespace {

void require_positive(const char* field, double v, bool allow_inf) {
    if (std::isnan(v) || v <= 0.0 || (!allow_inf && std::isinf(v))) {
        throw invalid_field(field, std::isnan(v) ? "nan" : format_length(v),
                            allow_inf ? "must be > 0 (inf allowed)" : "must be finite and > 0");
    }
}

}  // namespace

Camera paper_camera() { return Camera{}; }

void validate(const Camera& c) {
    require_positive("object_distance_m", c.object_distance_m, true);
    require_positive("lens_focal_m", c.lens_focal_m, true);
    require_positive("sensor_distance_m", c.sensor_distance_m, false);
    require_positive("wavelength_m", c.wavelength_m, false);
    require_positive("pixel_pitch_m", c.pixel_pitch_m, false);
    require_positive("pinhole_m", c.pinhole_m, false);
    if (c.sensor_cols < 1 || c.sensor_rows < 1) {
        throw invalid_field("sensor",
                            std::to_string(c.sensor_cols) + "x" + std::to_string(c.sensor_rows),
                            "width and height must be >= 1");
    }
}

}  // namespace pinmask
