// The noise level of a capture, read from the capture itself.
//
// Rule (Donoho and Johnstone's MAD estimator on the finest wavelet scale): the diagonal Haar
// detail of each 2 x 2 block, d = (p00 - p01 - p10 + p11) / 2, has variance sigma^2 for white
// noise of per-pixel variance sigma^2 and sees a smooth scene only through its second mixed
// derivative; sigma = median |d| / 0.6745 (the median absolute value of a unit Gaussian), which
// a minority of blocks on edges does not move. An odd last row or column is left out.
#pragma once

#include "core/image/image.hpp"

namespace pinmask {

// Per-pixel noise sigma of `capture`, in its units; 0 for a plane smaller than 2 x 2 or with
// no noise in its finest scale.
double estimate_noise_sigma(const Plane& capture);

}  // namespace pinmask
