#include "io/optics_json.hpp"

#include <string>

#include "core/errors/error.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {

using namespace json_strict;

Camera optics_from_json(const nlohmann::json& j) {
    ObjectReader r(j, "optics",
                   {"object_distance_m", "lens_focal_m", "sensor_distance_m", "wavelength_m",
                    "bandwidth_m", "pixel_pitch_m", "pinhole_m", "sensor_px"});
    r.reject_unknown();
    Camera c;
    c.object_distance_m =
        read_length_or_inf(r.required("object_distance_m"), r.path("object_distance_m"));
    c.lens_focal_m = read_length_or_inf(r.required("lens_focal_m"), r.path("lens_focal_m"));
    c.sensor_distance_m = read_number(r.required("sensor_distance_m"), r.path("sensor_distance_m"));
    c.wavelength_m = read_number(r.required("wavelength_m"), r.path("wavelength_m"));
    if (const nlohmann::json* b = r.optional("bandwidth_m"))
        c.bandwidth_m = read_number(*b, r.path("bandwidth_m"));
    c.pixel_pitch_m = read_number(r.required("pixel_pitch_m"), r.path("pixel_pitch_m"));
    c.pinhole_m = read_number(r.required("pinhole_m"), r.path("pinhole_m"));
    const auto [cols, rows] =
        read_int_pair(r.required("sensor_px"), r.path("sensor_px"), "[cols, rows]");
    c.sensor_cols = cols;
    c.sensor_rows = rows;
    try {
        validate(c);
    } catch (const InvalidInput& e) {
        throw InvalidInput(std::string("optics.") + e.what());
    }
    return c;
}

}  // namespace pinmask::io
