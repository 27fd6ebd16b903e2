#include "cli/options/analytic_setup.hpp"

#include <iomanip>
#include <sstream>

#include "cli/options/noise_options.hpp"
#include "io/json_strict.hpp"

namespace pinmask::cli {

using io::json_strict::finite_or_null;

void add_prior_flags(CLI::App& cmd, PriorFlags& f) {
    cmd.add_option("--prior", f.prior,
                   "Scene prior of the analytic error: natural (1/f textures), text (pages of "
                   "words), stars (sparse points on dark), or image files (comma-separated; "
                   "their power spectrum). The same prior in score, compare and search")
        ->capture_default_str();
    cmd.add_option("--prior-scenes", f.count,
                   "Sample scenes averaged for the natural, text or stars prior (1..4096)")
        ->capture_default_str();
}

PriorSpec prior_spec(const PriorFlags& f) { return parse_prior_spec(f.prior, f.count); }

std::vector<SceneSpec> scene_specs(const std::string& scenes) {
    return scene_specs_from_names(split_list(scenes, "--scenes"));
}

std::string metrics_table_text(const std::vector<nlohmann::ordered_json>& rows,
                               const MaskMetricsOptions& m) {
    std::vector<std::pair<std::string, std::string>> cols{{"holes", "K"}};
    if (m.sidelobes) {
        cols.push_back({"max_sidelobe", "max_sl"});
        cols.push_back({"peak_to_sidelobe_ratio", "PSR"});
    }
    if (m.spectrum) {
        cols.push_back({"min_abs_pattern_spectrum", "min|P|"});
        cols.push_back({"spectral_flatness", "flat"});
        cols.push_back({"otf_condition_number", "cond"});
    }
    for (const NoiseLevel& level : m.noise) {
        const std::string& k = level.key;
        if (m.analytic) cols.push_back({"analytic_mmse_psnr_db_" + k, "M" + k});
        if (m.analytic) cols.push_back({"analytic_wiener_psnr_db_" + k, "A" + k});
        if (m.analytic && m.robust.any())
            cols.push_back({"analytic_robust_wiener_psnr_db_" + k, "R" + k});
        if (m.wiener) cols.push_back({"sim_wiener_psnr_db_" + k, "W" + k});
        if (m.tv) cols.push_back({"sim_tv_psnr_db_" + k, "TV" + k});
        if (m.depth) {
            cols.push_back({"depth_crb_rel_" + k, "Du" + k});
            cols.push_back({"depth_axial_fwhm_m_" + k, "Dfw" + k});
        }
    }
    std::ostringstream s;
    s << std::left << std::setw(28) << "mask";
    for (const auto& c : cols) s << std::right << std::setw(11) << c.second;
    s << "\n";
    for (const auto& r : rows) {
        std::string name = r["mask"].get<std::string>();
        if (name.size() > 27) name = "..." + name.substr(name.size() - 24);
        s << std::left << std::setw(28) << name;
        for (const auto& c : cols) {
            const auto& v = r[c.first];
            std::ostringstream cell;
            if (v.is_null()) {
                cell << "inf";
            } else if (v.is_number_integer() || v.is_number_unsigned()) {
                cell << v.get<long long>();
            } else {
                cell << std::setprecision(4) << v.get<double>();
            }
            s << std::right << std::setw(11) << cell.str();
        }
        s << "\n";
    }
    for (const auto& r : rows) {
        if (r.contains("spectral_zero") && !r["spectral_zero"].is_null()) {
            s << "warning: " << r["mask"].get<std::string>() << ": "
              << r["spectral_zero"]["message"].get<std::string>() << "\n";
        }
    }
    s << "PSNR columns in dB over one period: A = analytic Wiener, W = simulated Wiener, TV = "
         "simulated TV-L2; suffix snrS = Gaussian noise at S dB, phP = the photon model at P "
         "electrons per pinhole. --json for every key.\n";
    if (m.depth) {
        s << "Du = the worst relative Cramer-Rao bound sigma_u / u of a point source's distance, "
             "Dfw = the worst axial resolution 2.355 sigma_u in metres, over "
          << (m.depth_range.from_m > 0 ? "the --depth-from/--depth-to range"
                                       : "the working distance / 2 .. x 2")
          << " (depth_from_m, depth_to_m in --json).\n";
    }
    if (m.analytic && m.robust.any()) {
        s << "R = analytic Wiener expected under fabrication errors (" << m.robust.description()
          << "), decoded with the nominal PSF, same NSR as A.\n";
    }
    return s.str();
}

}  // namespace pinmask::cli
