#include "cli/search_outputs.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "core/atomic_file.hpp"

namespace pinmask::cli {
namespace fs = std::filesystem;

namespace {

std::string fmt(double v, const char* spec = "%.3f") {
    if (std::isnan(v)) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, spec, v);
    return buf;
}

double score_or_nan(const Mask& m, const char* key) {
    const auto it = m.provenance.scores.find(key);
    return it == m.provenance.scores.end() ? NAN : it->second;
}

}  // namespace

std::string search_summary_markdown(const std::vector<RankedMask>& ranked,
                                    const SearchSummary& summary) {
    std::ostringstream s;
    s << "| rank | geometry hash | objective | analytic Wiener PSNR (dB) | simulated Wiener PSNR "
         "(dB) | simulated TV PSNR (dB) | max sidelobe / K | min |P^| / sqrt(K) |\n"
      << "|---:|---|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t i = 0; i < ranked.size(); ++i) {
        const Mask& m = ranked[i].mask;
        s << "| " << i + 1 << " | " << geometry_hash(m) << " | " << fmt(ranked[i].objective, "%.4f")
          << " | " << fmt(score_or_nan(m, "analytic_wiener_psnr_db")) << " | "
          << fmt(ranked[i].sim_wiener_psnr_db) << " | " << fmt(ranked[i].sim_tv_psnr_db) << " | "
          << fmt(score_or_nan(m, "max_sidelobe")) << " | " << fmt(-score_or_nan(m, "min_spectrum"))
          << " |\n";
    }
    s << "\n"
      << summary.evaluations << " evaluations in " << fmt(summary.seconds, "%.2f") << " s ("
      << summary.stop_reason << "); per chain:";
    for (auto e : summary.evaluations_per_chain) s << " " << e;
    s << "\n";
    return s.str();
}

std::vector<fs::path> write_search_outputs(const fs::path& dir,
                                           const std::vector<RankedMask>& ranked,
                                           const SearchSummary& summary,
                                           const nlohmann::ordered_json& config) {
    fs::create_directories(dir);
    StagedFiles files;
    std::vector<fs::path> paths;
    for (std::size_t i = 0; i < ranked.size(); ++i) {
        const fs::path p = dir / ("rank-" + std::to_string(i + 1) + ".mask.json");
        files.stage(p, [&](const fs::path& tmp) { io::write_mask_file(tmp, ranked[i].mask); });
        paths.push_back(p);
    }
    std::ostringstream log;
    log << "seconds,evaluations,best_objective\n";
    for (const auto& row : summary.log) {
        if (!std::isfinite(row.best_objective)) continue;  // before the first evaluation
        log << fmt(row.seconds, "%.3f") << "," << row.evaluations << ","
            << fmt(row.best_objective, "%.9g") << "\n";
    }
    files.stage_bytes(dir / "run-log.csv", log.str());
    files.stage_bytes(dir / "summary.md",
                      "# Search summary\n\n" + search_summary_markdown(ranked, summary));
    files.stage_bytes(dir / "search.config.json", io::json_strict::pretty(config) + "\n");
    files.commit();
    return paths;
}

}  // namespace pinmask::cli
