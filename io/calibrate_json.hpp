// The results of `pinmask calibrate` as JSON (the --json output and calibration.json's
// "result"): the fitted keys (rotation_deg, pitch_px [x, y], position_px [x, y], the pinhole side,
// pinholes [{cell, position_px, gain, gain_sigma, in_frame, missing}], missing_pinholes
// [[row, col]] with the rule and its false-alarm rate, extra_spots [[x, y]], background (leak),
// optical density, dark level, noise model, chi^2, kernel_fit {model: residual}, psf) with their
// standard errors, and the paths of every file written into `dir`. The Python module returns the
// same rendering with arrays in place of the files (python/bind_calibrate.cpp).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "decode/calibrate/calibrate.hpp"
#include "decode/calibrate/calibrate_run.hpp"

namespace pinmask::io {

nlohmann::ordered_json calibration_result_json(const calibrate::CalibrationSummary& s,
                                               const std::filesystem::path& dir);

// Writes the calibration into the new or empty folder `dir`, all files or none (staged in a
// sibling folder, renamed last): psf.tiff (+ psf.json, its sidecar naming `mask_file`),
// psf-period.tiff when there is one, kernel.tiff, calibrated.mask.json, report.pdf (titled
// `title`) and calibration.json ({format, version, config, result: calibration_result_json}).
void write_calibration_files(const CalibrateReport& report, const std::filesystem::path& dir,
                             const nlohmann::ordered_json& config, const std::string& mask_file,
                             const std::string& title);

}  // namespace pinmask::io
