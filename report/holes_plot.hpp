// The pinhole-count figure of `search --holes A..B`, Cairo, same drawing to SVG and
// PNG: predicted (analytic) PSNR in dB of the best mask found at each pinhole count K, one
// polyline with markers on the left axis, and beside it the light gain K (light collected
// relative to one pinhole) as a dashed grey line on the right axis. x axis: K.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pinmask {

struct HolesPoint {
    int holes = 0;         // K
    double psnr_db = 0.0;  // predicted PSNR of the best mask at K (non-finite points skipped)
};

// Not atomic: stage the paths. InvalidInput without points, RuntimeFailure when Cairo fails.
void write_holes_svg(const std::filesystem::path& path, const std::vector<HolesPoint>& points,
                     const std::string& title);
void write_holes_png(const std::filesystem::path& path, const std::vector<HolesPoint>& points,
                     const std::string& title);

}  // namespace pinmask
