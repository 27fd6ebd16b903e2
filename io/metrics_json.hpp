// A mask's metrics as the keys of `pinmask score --json`: the groups computed, every noise level
// under its key, infinite figures as null. Every PSNR key names its filter and its prior, the same
// in score, compare, search, the report and Python (docs/commands.md, "Figure names"):
//   analytic_mmse_psnr_db_<level>      closed form over the scene prior, per-frequency optimal
//                                      (MMSE) Wiener filter
//   analytic_wiener_psnr_db_<level>    closed form over the scene prior, Wiener filter of one NSR,
//                                      that NSR in analytic_wiener_nsr_<level> (given or tuned)
//   analytic_robust_wiener_psnr_db_<level>, analytic_robust_wiener_loss_db_<level>
//                                      the previous under fabrication errors (--robust), decoded
//                                      with the nominal PSF, and its loss against it
//   sim_wiener_psnr_db_<level>, sim_wiener_ssim_<level>, sim_wiener_nsr_<level>
//   sim_tv_psnr_db_<level>, sim_tv_ssim_<level>, sim_tv_lambda_<level>
//                                      simulated captures of the scenes, decoded, mean over scenes
// The depth group adds depth_from_m, depth_to_m and per level depth_crb_rel_<level> (the worst
// relative Cramer-Rao bound sigma_u / u over the range), depth_axial_fwhm_m_<level> (the worst
// 2.355 sigma_u, metres) and depth_worst_distance_m_<level> (the u of the first). Shared by the
// command and the Python module (score()), so both faces report the same keys and values.
#pragma once

#include <nlohmann/json.hpp>

#include "optimize/metrics/mask_metrics.hpp"

namespace pinmask::io {

// Adds m's figures to `row`; per-scene figures go to `per_scene` when given
// ({scene: {sim_wiener_psnr_db_snr30, ...}}).
void metrics_json(const MaskMetrics& m, nlohmann::ordered_json& row,
                  nlohmann::ordered_json* per_scene = nullptr);

}  // namespace pinmask::io
