// The depth figure (Cairo): PSNR loss (dB) of Wiener and TV against object distance. The x axis
// is 1/u (equal steps of pitch; u = inf at 0), ticks labelled with the distance; one polyline per
// decoder with markers, a dashed line at the mask's design distance. Same drawing to SVG and PNG.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "optimize/metrics/depth_loss.hpp"

namespace pinmask {

// Not atomic: stage the paths. Throws InvalidInput without records, RuntimeFailure when Cairo
// fails.
void write_depth_svg(const std::filesystem::path& path, const std::vector<DepthRecord>& records,
                     double design_distance_m, const std::string& title);
void write_depth_png(const std::filesystem::path& path, const std::vector<DepthRecord>& records,
                     double design_distance_m, const std::string& title);

}  // namespace pinmask
