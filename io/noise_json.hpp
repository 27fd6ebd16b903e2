// A noise model as the JSON the commands print and write in their configs: {"kind": "none" |
// "gaussian-snr" | "photon", and the model's parameters} (infinite figures as null).
#pragma once

#include <nlohmann/json.hpp>

#include "optimize/simulate/noise_model.hpp"

namespace pinmask::io {

nlohmann::ordered_json noise_json(const NoiseModel& model);

}  // namespace pinmask::io
