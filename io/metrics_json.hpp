// A mask's metrics as the keys of `pinmask score --json` (max_sidelobe,
// analytic_wiener_psnr_db_snr30, wiener_psnr_db_ph200, ...): the groups computed, every noise
// level under its key, infinite figures as null. Shared by the command and the Python module
// (score()), so both faces report the same keys and values.
#pragma once

#include <nlohmann/json.hpp>

#include "metrics/mask_metrics.hpp"

namespace pinmask::io {

// Adds m's figures to `row`; per-scene figures go to `per_scene` when given
// ({scene: {wiener_psnr_db_snr30, ...}}).
void metrics_json(const MaskMetrics& m, nlohmann::ordered_json& row,
                  nlohmann::ordered_json* per_scene = nullptr);

}  // namespace pinmask::io
