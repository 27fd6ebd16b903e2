// Small value conversions shared by the binding files.
#pragma once

#include <optional>
#include <string>

#include "python/common.hpp"

namespace pinmask::python {

// A length from a float (metres) or a string with a unit ("440um"); `field` names it in errors.
double length_value(const py::handle& v, const std::string& field, bool allow_inf);

}  // namespace pinmask::python

#include "design/pattern/mask.hpp"
#include "optimize/metrics/noise_levels.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask::python {

// The noise model of `pinmask simulate` / `score` flags: photons (photon model with the sensor
// stages) or snr_db (Gaussian; +inf = noiseless; default 30 dB). Same checks and messages.
struct NoiseArgs {
    std::optional<double> snr_db, photons, read_noise, dark_current, full_well, optical_density;
    std::optional<int> bits;
};
NoiseModel noise_model(const NoiseArgs& a);
// The sensor stages of the args (optimize/metrics/noise_levels.hpp).
SensorSettings sensor_settings(const NoiseArgs& a);

// A mask argument: a Mask, or a path to a *.mask.json.
Mask mask_arg(const py::handle& obj, bool allow_spacing_violations = false);

}  // namespace pinmask::python
