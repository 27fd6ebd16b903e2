// A mask's metrics as the keys of `pinmask score --json` (max_sidelobe,
// analytic_wiener_psnr_db_snr30, wiener_psnr_db_ph200, ...): the groups computed, every noise
// level under its key, infinite figures as null. The depth group adds depth_from_m, depth_to_m
// and per level depth_crb_rel_<level> (the worst relative Cramer-Rao bound sigma_u / u over the
// range), depth_axial_fwhm_m_<level> (the worst 2.355 sigma_u, metres) and
// depth_worst_distance_m_<level> (the u of the first). Shared by the command and the Python module
// (score()), so both faces report the same keys and values.
#pragma once

#include <nlohmann/json.hpp>

#include "optimize/metrics/mask_metrics.hpp"

namespace pinmask::io {

// Adds m's figures to `row`; per-scene figures go to `per_scene` when given
// ({scene: {wiener_psnr_db_snr30, ...}}).
void metrics_json(const MaskMetrics& m, nlohmann::ordered_json& row,
                  nlohmann::ordered_json* per_scene = nullptr);

}  // namespace pinmask::io
