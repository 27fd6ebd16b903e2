// The `pinmask design` report as a table (cli/cmd_design.cpp); its JSON is io/design_json.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli/options/camera_options.hpp"
#include "design/optics/design_run.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/design_kernel.hpp"

namespace pinmask::cli {

// The table (quantity, value, note), after the inputs used (symbol, value, source); `solved`
// non-empty says the pinhole was solved for N at u.
std::string design_table(const OpticsReport& r, const WorkingDistance& wd,
                         const std::string& solved, const std::vector<CameraInput>& inputs,
                         const GridSnap& snap = {}, const DesignKernel& dk = {});

}  // namespace pinmask::cli
