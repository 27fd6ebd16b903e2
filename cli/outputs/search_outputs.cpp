#include "cli/outputs/search_outputs.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "cli/outputs/search_snapshot.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_set.hpp"
#include "core/units/number_format.hpp"
#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "optimize/metrics/figure_names.hpp"
#include "report/holes_plot.hpp"

namespace pinmask::cli {
namespace fs = std::filesystem;

namespace {

double score_or_nan(const Mask& m, const std::string& key) {
    const auto it = m.provenance.scores.find(key);
    return it == m.provenance.scores.end() ? NAN : it->second;
}

// The analytic figure the summary's tables show: the one the objective weighs, else the MMSE one.
std::string shown_figure(const SearchPipelineSummary& s) {
    return s.objective_figure.empty() ? "analytic_mmse_psnr_db" : s.objective_figure;
}

// The robust figure's key among a mask's scores and the nominal figure it is set against.
std::pair<std::string, std::string> robust_keys(const Mask& m) {
    for (const char* k : {"analytic_robust_filter_psnr_db", "analytic_robust_mmse_psnr_db",
                          "analytic_robust_wiener_psnr_db"}) {
        if (!m.provenance.scores.count(k)) continue;
        const std::string key = k;
        if (key == "analytic_robust_filter_psnr_db")
            return {key, "analytic_robust_filter_nominal_psnr_db"};
        return {key, key == "analytic_robust_mmse_psnr_db" ? "analytic_mmse_psnr_db"
                                                           : "analytic_wiener_psnr_db"};
    }
    return {"", ""};
}

// "Best possible for K holes <= X dB" (optimize/search/objective_bound): for rank 1's K, and with a
// pinhole-count range the largest bound over the range's K.
std::string bound_summary(const SearchPipelineSummary& summary) {
    if (summary.ranked.empty() || !std::isfinite(summary.ranked.front().upper_bound_psnr_db))
        return "";
    const RankedMask& top = summary.ranked.front();
    std::ostringstream s;
    // The bound is on the analytic MMSE PSNR (the optimal filter): rank 1 is set against it on
    // that same figure, and the searched figure follows when it is another filter's.
    s << "\nBest possible for " << top.mask.pattern.pinholes.size()
      << " holes <= " << format_cell(top.upper_bound_psnr_db)
      << " dB analytic MMSE PSNR (any pattern with that K, per-frequency optimal filter, which "
         "no linear decoder beats; this kernel, prior and noise); rank 1: "
      << format_cell(score_or_nan(top.mask, "analytic_mmse_psnr_db")) << " dB on the same figure";
    if (summary.objective_figure == "analytic_wiener_psnr_db") {
        s << " (" << format_cell(score_or_nan(top.mask, "analytic_wiener_psnr_db"))
          << " dB analytic Wiener PSNR at NSR "
          << format_cell(score_or_nan(top.mask, "analytic_wiener_nsr"), "%.3g")
          << ", the figure searched)";
    }
    s << ".\n";
    const RankedMask* best = nullptr;
    for (const RankedMask& r : summary.best_per_holes)
        if (std::isfinite(r.upper_bound_psnr_db) &&
            (!best || r.upper_bound_psnr_db > best->upper_bound_psnr_db))
            best = &r;
    if (best) {
        s << "Best possible for any K searched <= " << format_cell(best->upper_bound_psnr_db)
          << " dB (K = " << best->mask.pattern.pinholes.size() << ").\n";
    }
    return s.str();
}

}  // namespace

std::string search_summary_markdown(const SearchPipelineSummary& summary) {
    std::ostringstream s;
    // Every PSNR column names what it is computed on: the analytic figure over the prior in
    // closed form, the simulated ones on the re-rank scenes.
    std::string scenes;
    for (const std::string& n : summary.rerank_scene_names)
        scenes += (scenes.empty() ? "" : "+") + n;
    if (scenes.empty()) scenes = "none";
    const std::string shown = shown_figure(summary);
    s << "| rank | geometry hash | objective | " << figure_words(shown) << " (dB; " << shown
      << ", closed form, prior " << summary.prior_description
      << ") | simulated Wiener PSNR (dB; sim_wiener_psnr_db, scenes " << scenes
      << ", NSR tuned) | simulated TV PSNR (dB; sim_tv_psnr_db, scenes " << scenes
      << ") | max sidelobe | min |P^| |\n"
      << "|---:|---|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t i = 0; i < summary.ranked.size(); ++i) {
        const RankedMask& r = summary.ranked[i];
        const Mask& m = r.mask;
        s << "| " << i + 1 << " | " << geometry_hash(m) << " | " << format_cell(r.objective, "%.4f")
          << " | " << format_cell(score_or_nan(m, shown)) << " | "
          << format_cell(r.sim_wiener_psnr_db) << " | " << format_cell(r.sim_tv_psnr_db) << " | "
          << format_cell(score_or_nan(m, "max_sidelobe"), "%.0f") << " | "
          << format_cell(score_or_nan(m, "min_abs_pattern_spectrum")) << " |\n";
    }
    // --robust: the expected PSNR under fabrication errors beside the nominal figure.
    const auto [robust, nominal] = summary.ranked.empty()
                                       ? std::pair<std::string, std::string>{}
                                       : robust_keys(summary.ranked.front().mask);
    if (!robust.empty()) {
        s << "\nAnalytic PSNR (dB), nominal (" << nominal << ") -> expected under the --robust "
          << "fabrication errors (" << robust << "):";
        for (std::size_t i = 0; i < summary.ranked.size(); ++i) {
            const Mask& m = summary.ranked[i].mask;
            s << (i ? "," : "") << " rank " << i + 1 << " " << format_cell(score_or_nan(m, nominal))
              << " -> " << format_cell(score_or_nan(m, robust));
        }
        s << "\n";
    }
    const SearchSummary& sr = summary.search;
    s << "\n"
      << sr.evaluations << " evaluations; stopped: " << search_termination_name(summary.termination)
      << " (" << search_termination_message(summary.termination) << "); per chain:";
    for (auto e : sr.evaluations_per_chain) s << " " << e;
    s << "\nRe-ranked by simulation: " << summary.reranked << " of " << summary.ranked.size()
      << " candidates";
    if (summary.reranked > 1) {
        s << "; " << summary.reordered
          << " moved. A candidate moves above another only when its simulated PSNR is higher by "
             "more than the standard error of the per-scene difference ("
          << summary.rerank_scene_names.size()
          << " scenes); smaller differences are the simulation's noise and the objective's order "
             "stands";
    }
    s << ".\n";
    for (std::size_t i = 0; i < summary.ranked.size(); ++i) {
        if (summary.ranked[i].spectral_zero) {
            s << "WARNING: rank " << i + 1 << ": " << summary.ranked[i].spectral_zero_message
              << " (kept because of --allow-spectral-zeros)\n";
        }
    }
    if (!summary.best_per_holes.empty()) {
        s << "\nBest mask per pinhole count (predicted by the analytic objective; light gain = K "
             "times one pinhole's light):\n\n"
          << "| K | light gain | objective | " << figure_words(shown_figure(summary)) << " (dB; "
          << shown_figure(summary)
          << ") | bound on analytic MMSE PSNR (dB) | analytic MMSE PSNR (dB) | geometry hash | "
             "spectral zero |\n|---:|---:|---:|---:|---:|---:|---|---|\n";
        for (const RankedMask& r : summary.best_per_holes) {
            const std::size_t k = r.mask.pattern.pinholes.size();
            s << "| " << k << " | " << k << "x | " << format_cell(r.objective, "%.4f") << " | "
              << format_cell(score_or_nan(r.mask, shown_figure(summary))) << " | "
              << format_cell(r.upper_bound_psnr_db) << " | "
              << format_cell(score_or_nan(r.mask, "analytic_mmse_psnr_db")) << " | "
              << geometry_hash(r.mask) << " | " << (r.spectral_zero ? "yes" : "no") << " |\n";
        }
    }
    s << bound_summary(summary);
    if (summary.planned_s > 0.0) {  // timings only for time-budget runs (never reproducible)
        s << "Time: planned " << format_cell(summary.planned_s, "%.2f") << " s, used "
          << format_cell(summary.used_s, "%.2f") << " s (search "
          << format_cell(summary.search_s, "%.2f") << " s, re-ranking "
          << format_cell(summary.rerank_s, "%.2f") << " s, "
          << format_cell(summary.rerank_reserved_s, "%.2f") << " s reserved for it).\n";
    }
    return s.str();
}

std::vector<fs::path> write_search_outputs(const fs::path& dir,
                                           const SearchPipelineSummary& summary,
                                           const nlohmann::ordered_json& config) {
    fs::create_directories(dir);
    StagedFiles files;
    std::vector<fs::path> paths;
    for (std::size_t i = 0; i < summary.ranked.size(); ++i) {
        const fs::path p = dir / ("rank-" + std::to_string(i + 1) + ".mask.json");
        const Mask& mask = summary.ranked[i].mask;
        files.stage(p, [&](const fs::path& tmp) { io::write_mask_file(tmp, mask); });
        paths.push_back(p);
    }
    std::ostringstream log;
    log << "evaluations_per_chain,evaluations,best_objective\n";
    for (const auto& row : summary.search.checkpoints) {
        if (!std::isfinite(row.best_objective)) continue;  // before the first accepted pattern
        log << row.evaluations_per_chain << "," << row.evaluations << ","
            << format_cell(row.best_objective, "%.9g") << "\n";
    }
    files.stage_bytes(dir / "run-log.csv", log.str());
    std::ostringstream timing;
    timing << "seconds,evaluations,best_objective\n";
    for (const auto& row : summary.search.log) {
        if (!std::isfinite(row.best_objective)) continue;
        timing << format_cell(row.seconds, "%.3f") << "," << row.evaluations << ","
               << format_cell(row.best_objective, "%.9g") << "\n";
    }
    files.stage_bytes(dir / "timing.csv", timing.str());
    if (!summary.best_per_holes.empty()) {
        std::ostringstream csv;
        const std::string shown = shown_figure(summary);
        csv << "holes,light_gain,objective," << shown
            << ",spectral_zero,geometry_hash,upper_bound_analytic_mmse_psnr_db\n";
        std::vector<HolesPoint> points;
        for (const RankedMask& r : summary.best_per_holes) {
            const int k = static_cast<int>(r.mask.pattern.pinholes.size());
            const double psnr = score_or_nan(r.mask, shown);
            csv << k << "," << k << "," << format_cell(r.objective, "%.9g") << ","
                << format_cell(psnr, "%.9g") << "," << (r.spectral_zero ? 1 : 0) << ","
                << geometry_hash(r.mask) << "," << format_cell(r.upper_bound_psnr_db, "%.9g")
                << "\n";
            points.push_back({k, psnr});
            const fs::path p = dir / ("best-K" + std::to_string(k) + ".mask.json");
            files.stage(p, [&](const fs::path& tmp) { io::write_mask_file(tmp, r.mask); });
        }
        files.stage_bytes(dir / "holes.csv", csv.str());
        const std::string title = "search: predicted PSNR of the best mask per pinhole count";
        files.stage(dir / "holes.svg",
                    [&](const fs::path& tmp) { write_holes_svg(tmp, points, title); });
        files.stage(dir / "holes.png",
                    [&](const fs::path& tmp) { write_holes_png(tmp, points, title); });
    }
    files.stage_bytes(dir / "summary.md",
                      "# Search summary\n\n" + search_summary_markdown(summary));
    files.stage_bytes(dir / "search.config.json", io::json_strict::pretty(config) + "\n");
    files.commit();
    return paths;
}

std::string search_explain_text(const SearchPipelineSummary& s, bool allow_spectral_zeros) {
    const PriorRelevance& pr = s.prior_relevance;
    std::ostringstream out;
    out << "explain: prior " << s.prior_description << ": " << pr.irrelevant << " of " << pr.total
        << " frequencies carry < 1e-6 of its peak power (irrelevant to the objective); "
           "relevant up to radius "
        << pr.highest_relevant_radius
        << " cycles per period. Skipped: nothing (the objective still sums every "
           "frequency; patterns with a spectral zero where the kernel passes light "
        << (allow_spectral_zeros ? "were kept, flagged" : "were rejected") << ")\n";
    return out.str();
}

void plan_search_outputs(const std::filesystem::path& dir, bool per_holes,
                         const std::string& config) {
    std::vector<NamedPath> outs{{"-o (run log)", dir / "run-log.csv", true},
                                {"-o (summary)", dir / "summary.md", true},
                                {"-o (timing)", dir / "timing.csv", true},
                                {"-o (config)", dir / "search.config.json", true},
                                {"-o (best so far)", dir / kBestSoFarName, true}};
    if (per_holes)
        for (const char* f : {"holes.csv", "holes.svg", "holes.png"})
            outs.push_back({"-o (per-K table and plot)", dir / f, true});
    plan_outputs({{"--config", config}}, outs);
}

}  // namespace pinmask::cli
