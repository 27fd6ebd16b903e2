// The single-pinhole kernel calibrate reports: the fitted kernel sampled on a window of
// (2 half + 1)^2 pixels around its centre, normalised to sum 1 (decode/calibrate/forward_fit).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask::calibrate {

struct KernelEstimate {
    Plane values;  // (2 half + 1)^2, sum 1
    int half_px = 0;
    int spots_used = 0;
};

}  // namespace pinmask::calibrate
