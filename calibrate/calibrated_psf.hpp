// PSFs from a calibration: the measured kernel placed at every pinhole's spot.
//   full frame (linear): the capture's size; each found pinhole's kernel at its lattice position
//     (plus its own residual when that exceeds kResidualSignificance x the fit's rms), weighted
//     by its gain; merged spots split evenly over their predicted sites; extra spots at their
//     centroids with their flux; missing pinholes absent. Sum 1.
//   one period (cyclic): when the lattice vectors of n cells are within period_tolerance_px of
//     whole pixels (Nc, 0) and (0, Nr): a Nr x Nc torus with pattern cell (r, c) at
//     (c + 1/2) Nc/n - 1/2, (r + 1/2) Nr/n - 1/2 (design/kernel's placement at the measured
//     pitch), weighted by the mean gain of its copies in frame (missing copies count 0, a cell
//     with no copy in frame counts 1). Sum 1.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "calibrate/kernel_estimate.hpp"
#include "calibrate/pinholes.hpp"
#include "calibrate/registration.hpp"
#include "calibrate/spots.hpp"
#include "core/image.hpp"
#include "design/pattern.hpp"

namespace pinmask::calibrate {

inline constexpr double kResidualSignificance = 3.0;

struct CalibratedPsfs {
    Plane full_frame;
    std::optional<Plane> period;
    std::string period_reason;  // why the period PSF was or was not made
    double period_drift_px = 0.0;
};

CalibratedPsfs calibrated_psfs(int rows, int cols, const KernelEstimate& kernel,
                               const std::vector<Spot>& spots, const PinholeMatch& match,
                               const LatticeFit& fit, const Pattern& pattern,
                               double period_tolerance_px);

}  // namespace pinmask::calibrate
