// The results of `pinmask calibrate` as JSON (the --json output and calibration.json's
// "result"): the fitted keys (rotation_deg, pitch_px [x, y], position_px [x, y], the pinhole side,
// pinholes [{cell, position_px, gain, gain_sigma, in_frame, missing}], missing_pinholes
// [[row, col]] with the rule and its false-alarm rate, extra_spots [[x, y]], background (leak),
// optical density, dark level, noise model, chi^2, kernel_fit {model: residual}, psf) with their
// standard errors, and the paths of every file written into `dir`. The Python module builds the
// same keys (python/bind_calibrate.cpp).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "decode/calibrate/calibrate.hpp"

namespace pinmask::cli {

nlohmann::ordered_json calibration_result_json(const calibrate::CalibrationSummary& s,
                                               const std::filesystem::path& dir);

}  // namespace pinmask::cli
