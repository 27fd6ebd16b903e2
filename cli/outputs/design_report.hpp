// Rendering of the `pinmask design` report (cli/cmd_design.cpp): table and JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/options/camera_options.hpp"
#include "design/optics.hpp"
#include "design/working_distance.hpp"

namespace pinmask::cli {

// One JSON object: camera, geometry, every OpticsReport and WorkingDistance figure (unit-suffixed
// keys), "notes" (key -> why a value is null).
nlohmann::ordered_json design_json(const OpticsReport& r, const WorkingDistance& wd);

// The table (quantity, value, note), after the inputs used (symbol, value, source); `solved`
// non-empty says the pinhole was solved for N at u.
std::string design_table(const OpticsReport& r, const WorkingDistance& wd,
                         const std::string& solved, const std::vector<CameraInput>& inputs);

}  // namespace pinmask::cli
