// Rendering of the `pinmask design` report (cli/cmd_design.cpp): table and JSON.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/options/camera_options.hpp"
#include "design/optics/design_run.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/design_kernel.hpp"

namespace pinmask::cli {

// One JSON object: camera, geometry, every OpticsReport and WorkingDistance figure (unit-suffixed
// keys: plain and "_at_u" keys at the working distance u, "_at_inf" keys for a distant object),
// "notes" (key -> why a value is null), and the kernel psf would build (`dk`): "spectrum"
// (bandwidth_m, wavelengths [[m, weight], ...]) and "kernel" (support_px, enclosed_energy).
nlohmann::ordered_json design_json(const OpticsReport& r, const WorkingDistance& wd,
                                   const GridSnap& snap = {}, const DesignKernel& dk = {});

// The table (quantity, value, note), after the inputs used (symbol, value, source); `solved`
// non-empty says the pinhole was solved for N at u.
std::string design_table(const OpticsReport& r, const WorkingDistance& wd,
                         const std::string& solved, const std::vector<CameraInput>& inputs,
                         const GridSnap& snap = {}, const DesignKernel& dk = {});

}  // namespace pinmask::cli
