// `pinmask depth --json` from the depth analysis (optimize/metrics/depth_loss depth_analysis): one
// record per object distance (pitch, period, shift-invariance mismatch, the PSNR lost by the
// integer cyclic PSF; infinities as null). The command prints it and writes it inside
// depth.json; Python's depth() returns it.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "optimize/metrics/depth_loss.hpp"

namespace pinmask::io {

nlohmann::ordered_json depth_json(const std::vector<DepthRecord>& records);

// Writes dir/depth.svg and dir/depth.png (report/depth_plot, titled `title`, the design distance
// `design_u_m` marked) and dir/depth.json (`config` with "records": depth_json), all or none,
// creating dir; returns the paths written.
std::vector<std::filesystem::path> write_depth_files(const std::filesystem::path& dir,
                                                     const std::vector<DepthRecord>& records,
                                                     double design_u_m, const std::string& title,
                                                     nlohmann::ordered_json config);

}  // namespace pinmask::io
