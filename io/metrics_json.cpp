#include "io/metrics_json.hpp"

#include <string>
#include <utility>

#include "io/json_strict.hpp"

namespace pinmask::io {

using json_strict::finite_or_null;

void metrics_json(const MaskMetrics& m, nlohmann::ordered_json& row,
                  nlohmann::ordered_json* per_scene) {
    if (m.sidelobes) {
        const SidelobeMetrics& s = *m.sidelobes;
        row["peak_autocorrelation"] = s.peak;
        row["max_sidelobe"] = s.max_sidelobe;
        row["mean_sidelobe"] = s.mean_sidelobe;
        row["integrated_sidelobe_level"] = s.integrated_sidelobe_level;
        row["peak_to_sidelobe_ratio"] = finite_or_null(s.peak_to_sidelobe_ratio);
    }
    if (m.spectrum) {
        const PatternSpectrumMetrics& s = *m.spectrum;
        row["min_abs_pattern_spectrum"] = s.min_abs_pattern_spectrum;
        row["spectral_flatness"] = s.spectral_flatness;
        row["open_fraction"] = s.open_fraction;
        row["light_gain"] = s.light_gain;
        row["otf_condition_number"] = finite_or_null(m.otf->condition_number);
        row["otf_passband_frequencies"] = m.otf->passband_frequencies;
        const SpectralZero& z = *m.spectral_zero;
        if (z.found) {
            row["spectral_zero"] = {{"frequency", {z.row, z.col}},
                                    {"abs_pattern_spectrum", z.abs_value},
                                    {"threshold", z.threshold_abs},
                                    {"count", z.count},
                                    {"message", z.message()}};
        } else {
            row["spectral_zero"] = nullptr;
        }
    }
    if (!m.levels.empty() && m.levels.front().depth) {
        row["depth_from_m"] = m.levels.front().depth->from_m;
        row["depth_to_m"] = m.levels.front().depth->to_m;
    }
    for (const LevelMetrics& l : m.levels) {
        const std::string& k = l.level.key;
        if (l.depth) {
            row["depth_crb_rel_" + k] = finite_or_null(l.depth->crb_rel);
            row["depth_axial_fwhm_m_" + k] = finite_or_null(l.depth->axial_fwhm_m);
            row["depth_worst_distance_m_" + k] = l.depth->worst_distance_m;
        }
        if (l.analytic) {
            row["analytic_wiener_psnr_db_" + k] = finite_or_null(l.analytic->psnr_db);
            row["analytic_wiener_nsr_" + k] = l.analytic->nsr;
            row["analytic_mmse_psnr_db_" + k] = finite_or_null(l.analytic->mmse_psnr_db);
        }
        if (l.robust) {
            row["analytic_robust_wiener_psnr_db_" + k] = finite_or_null(l.robust->psnr_db);
            row["analytic_robust_wiener_loss_db_" + k] = finite_or_null(l.robust->loss_db);
        }
        for (const auto& [metric, q] :
             {std::pair{std::string("wiener"), &l.wiener}, std::pair{std::string("tv"), &l.tv}}) {
            if (!*q) continue;
            const std::string weight = metric == "wiener" ? "nsr" : "lambda";
            const std::string name = "sim_" + metric;  // simulated on the scenes
            row[name + "_psnr_db_" + k] = finite_or_null((*q)->mean_psnr_db);
            row[name + "_ssim_" + k] = finite_or_null((*q)->mean_ssim);
            row[name + "_" + weight + "_" + k] = (*q)->weight;
            if (!per_scene) continue;
            for (const SceneQuality& s : (*q)->scenes) {
                (*per_scene)[s.scene][name + "_psnr_db_" + k] = finite_or_null(s.psnr_db);
                (*per_scene)[s.scene][name + "_ssim_" + k] = finite_or_null(s.ssim);
            }
        }
    }
}

}  // namespace pinmask::io
