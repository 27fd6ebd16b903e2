// The calibration report as PDF bytes (Cairo, A4 portrait, metadata dates pinned so the same
// calibration gives the same bytes):
//   page 1  the capture (grey, 1st to 99.9th percentile) with the predicted spot sites (circles:
//           green found, red missing, orange merged) and the measured centroids (crosses; blue
//           for extra spots), and the figures (rotation, pitch, position, background);
//   page 2  the residual map (capture - background - flux-scaled calibrated PSF, grey, symmetric
//           range) and the kernel comparison (the measured kernel, each available model on the
//           same window, residuals);
//   page 3+ the per-pinhole table (mask cell, state, predicted and measured position, residual,
//           gain).
#pragma once

#include <string>

#include "calibrate/calibrate.hpp"

namespace pinmask::calibrate {

// `capture` is the frame calibrated (after the dark frame); `title` goes on every page.
std::string calibration_report_pdf(const Plane& capture, const CalibrationSummary& summary,
                                   const std::string& title);

}  // namespace pinmask::calibrate
