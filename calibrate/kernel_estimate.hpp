// The single-pinhole kernel measured from a point-source capture: a window of (2 half + 1)^2
// pixels around each good spot is sampled at the spot's sub-pixel centroid (calibrate/subpixel,
// Lanczos-3) so every spot's centroid lands on the window's centre pixel, each window is divided
// by its spot's flux, and the windows are combined by the per-pixel median (robust to a
// neighbour's edge, a cosmic ray or a dust shadow in a few spots). The result is normalised to
// sum 1; its centroid is (half, half) up to the median's asymmetry.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/image.hpp"

namespace pinmask::calibrate {

struct KernelEstimate {
    Plane values;  // (2 half + 1)^2, sum 1
    int half_px = 0;
    int spots_used = 0;
};

// `frame` is the capture with the background already subtracted; `centres` the (x, y) centroids
// and `fluxes` the spots' fluxes (> 0). Throws InvalidInput when no spot is given or the median
// kernel has no positive sum.
KernelEstimate estimate_kernel(const Plane& frame, const std::vector<Eigen::Vector2d>& centres,
                               const std::vector<double>& fluxes, int half_px);

}  // namespace pinmask::calibrate
