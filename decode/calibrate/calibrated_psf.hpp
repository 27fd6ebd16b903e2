// PSFs from the fit of the forward model (decode/calibrate/forward_fit):
//   full frame (linear): the capture's size; every open cell's kernel at its fitted spot centre
//     with its fitted gain (missing pinholes absent, tails included). Sum 1.
//   one period (cyclic): when the lattice vectors of n cells are within period_tolerance_px of
//     whole pixels (Nc, 0) and (0, Nr): a Nr x Nc torus with pattern cell (r, c) at
//     (c + 1/2) Nc/n - 1/2, (r + 1/2) Nr/n - 1/2 (design/psf/kernel's placement at the measured
//     pitch), the fitted kernel wrapped, weighted by the mean gain of its copies in frame
//     (missing copies count 0, a cell with no copy in frame counts the median). Sum 1.
#pragma once

#include <optional>
#include <string>

#include "core/image/image.hpp"
#include "decode/calibrate/forward_fit.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask::calibrate {

struct CalibratedPsfs {
    Plane full_frame;
    std::optional<Plane> period;
    std::string period_reason;  // why the period PSF was or was not made
    double period_drift_px = 0.0;
};

CalibratedPsfs calibrated_psfs(int rows, int cols, const ForwardFit& fit, const Mask& mask,
                               double period_tolerance_px);

// The fitted kernel (side fit.side_m, the fit's family) on a (2 half + 1)^2 window centred on
// its middle pixel, unrotated, sum 1.
Plane fitted_kernel(const ForwardFit& fit, const Mask& mask, int half);

}  // namespace pinmask::calibrate
