// The calibration report as PDF bytes (Cairo, A4 portrait, metadata dates pinned so the same
// calibration gives the same bytes):
//   page 1  the capture (grey, 1st to 99.9th percentile) with the fitted spot sites (circles:
//           green found, red missing) and extra light (blue crosses), and the uncertainty table:
//           measured against design lattice (rotation, pitches, pinhole side), position, leak,
//           optical density, noise model, chi^2, the missing rule and the coverage tested;
//   page 2  the residual map (capture - fitted model, grey, symmetric range) and the kernel
//           comparison (the fitted kernel, each available design model on the same window);
//   page 3+ the per-pinhole table (mask cell, state, fitted position, gain +- sigma).
#pragma once

#include <string>

#include "decode/calibrate/calibrate.hpp"

namespace pinmask::calibrate {

// `capture` is the frame calibrated (after the dark frame); `title` goes on every page.
std::string calibration_report_pdf(const Plane& capture, const CalibrationSummary& summary,
                                   const std::string& title);

}  // namespace pinmask::calibrate
