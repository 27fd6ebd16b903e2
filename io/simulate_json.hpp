// OUT.config.json of `pinmask simulate`: the resolved configuration (mask, kernel, scene, noise,
// seed, tiling, units, outputs, the --explain lines) beside the capture.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/simulate/simulate_pipeline.hpp"

namespace pinmask::io {

struct SimulateConfigInputs {
    std::string mask_path, output, dark_frame;  // dark_frame empty: none
    std::string geometry;                       // integer | exact
    bool full_sensor = false;
    std::uint64_t seed = 1;
};

// The per-channel background of the capture, as a JSON array.
nlohmann::ordered_json background_json(const SimulatedCapture& s);

nlohmann::ordered_json simulate_config_json(const SimulateConfigInputs& in, const Mask& mask,
                                            const SimulatePipelineOptions& po,
                                            const SimulatePipelineResult& r,
                                            const std::vector<std::string>& explain);

// The one-line --json summary on stdout: outputs, size, channels, period, noise, background.
nlohmann::ordered_json simulate_summary_json(const SimulateConfigInputs& in,
                                             const SimulatePipelineResult& r,
                                             const NoiseModel& noise);

}  // namespace pinmask::io
