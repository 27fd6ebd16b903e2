// The results of `pinmask calibrate` as JSON (the --json output and calibration.json's
// "result"): the measured keys (rotation_deg, pitch_px [x, y], position_px [x, y],
// missing_pinholes [[row, col]], extra_spots [[x, y]], background, kernel_fit {model: residual},
// psf) plus uncertainties, merged/oversized pinholes, dark level, optical density, the kernel
// models design/ cannot make and the paths of every file written into `dir`.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "calibrate/calibrate.hpp"

namespace pinmask::cli {

nlohmann::ordered_json calibration_result_json(const calibrate::CalibrationSummary& s,
                                               const std::filesystem::path& dir);

}  // namespace pinmask::cli
