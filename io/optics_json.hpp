// The "optics" object of pinmask's JSON files (mask files, search configurations): a Camera in
// SI units, {"object_distance_m" (number or "inf"), "lens_focal_m" (number or "inf"),
// "sensor_distance_m", "wavelength_m", "bandwidth_m" (optional), "pixel_pitch_m", "pinhole_m",
// "sensor_px": [cols, rows]}. Every key is written and required on reading, except bandwidth_m:
// written only when it is not 0 and read as 0 when absent, so files from before it read the same
// and a monochromatic camera writes the same bytes. Unknown keys are refused.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>

#include "design/optics/camera.hpp"

namespace pinmask::io {

// Reads and validates (design/optics/camera) the object; InvalidInput names "optics.<key>" and the
// rule.
Camera optics_from_json(const nlohmann::json& j);

// The object, keys in the order above (J: nlohmann::json or nlohmann::ordered_json).
template <class J>
J optics_to_json(const Camera& c) {
    auto length_or_inf = [](double v) { return std::isinf(v) ? J("inf") : J(v); };
    J optics;
    optics["object_distance_m"] = length_or_inf(c.object_distance_m);
    optics["lens_focal_m"] = length_or_inf(c.lens_focal_m);
    optics["sensor_distance_m"] = c.sensor_distance_m;
    optics["wavelength_m"] = c.wavelength_m;
    if (c.bandwidth_m != 0.0) optics["bandwidth_m"] = c.bandwidth_m;
    optics["pixel_pitch_m"] = c.pixel_pitch_m;
    optics["pinhole_m"] = c.pinhole_m;
    optics["sensor_px"] = J::array({c.sensor_cols, c.sensor_rows});
    return optics;
}

}  // namespace pinmask::io
