#include "io/compare_json.hpp"

#include "core/files/atomic_file.hpp"
#include "io/json_strict.hpp"
#include "io/metrics_json.hpp"
#include "io/noise_json.hpp"

namespace pinmask::io {

using json_strict::finite_or_null;

nlohmann::ordered_json compare_row_json(const CompareRow& r) {
    nlohmann::ordered_json j{{"name", r.name},
                             {"kind", r.kind},
                             {"source", r.source},
                             {"geometry_hash", r.geometry_hash},
                             {"n", r.n},
                             {"holes", r.holes},
                             {"pixels_per_cell", r.pixels_per_cell},
                             {"period_px", r.period_px},
                             {"min_spacing_cells", r.min_spacing_cells},
                             {"spacing_ok", r.spacing_ok},
                             {"spacing_violations", r.spacing_violations},
                             {"analytic_wiener_psnr_db", finite_or_null(r.analytic_wiener_psnr_db)},
                             {"wiener_psnr_db", finite_or_null(r.wiener_psnr_db)},
                             {"wiener_ssim", finite_or_null(r.wiener_ssim)},
                             {"wiener_nsr", r.wiener_nsr},
                             {"tv_psnr_db", finite_or_null(r.tv_psnr_db)},
                             {"tv_ssim", finite_or_null(r.tv_ssim)},
                             {"tv_lambda", r.tv_lambda}};
    metrics_json(r.metrics, j);  // every level with score's keys
    return j;
}

nlohmann::ordered_json compare_json(const CompareReport& report) {
    const CompareRequest& q = report.request;
    const CompareOutcome& out = report.outcome;
    const MaskMetricsOptions& mo = report.options.settings.metrics;
    nlohmann::ordered_json j;
    for (const auto& r : out.results) j["masks"].push_back(compare_row_json(r.row));
    j["psnr_columns"] = {{"analytic_wiener_psnr_db", report.analytic_basis},
                         {"wiener_psnr_db", report.sim_basis + ", Wiener " + report.nsr_words},
                         {"tv_psnr_db", report.sim_basis + ", TV-L2 lambda " + q.tv_lambda}};
    nlohmann::ordered_json levels = nlohmann::ordered_json::array();
    for (const NoiseLevel& l : mo.noise) levels.push_back(noise_json(l.model));
    j["settings"] = {{"noise", levels},
                     {"scenes", report.scenes},
                     {"prior", mo.prior.description()},
                     {"wiener_nsr", q.wiener_nsr},
                     {"tv_lambda", q.tv_lambda},
                     {"tv_iterations", q.tv_iterations},
                     {"seed", q.seed},
                     {"baselines", q.baselines},
                     {"baseline_count", q.baseline_count},
                     {"robust", mo.robust.description()}};
    if (mo.depth) {
        j["settings"]["depth_from_m"] = q.depth_from_m;  // 0: the working distance / 2
        j["settings"]["depth_to_m"] = q.depth_to_m;      // 0: twice the working distance
    }
    if (q.baselines) {
        nlohmann::ordered_json b;
        if (out.random) {
            b["random"] = {{"count", out.random->count},
                           {"first_seed", q.seed},
                           {"median_seed", out.random->median_seed},
                           {"min_wiener_psnr_db", out.random->min_psnr_db},
                           {"median_wiener_psnr_db", out.random->median_psnr_db},
                           {"max_wiener_psnr_db", out.random->max_psnr_db}};
        } else {
            b["random"] = {{"skipped", out.random_skipped}};
        }
        b["paper_like"] = {{"seed", q.seed}};
        b["mura"] = out.mura_order > 0 ? nlohmann::ordered_json{{"order", out.mura_order}}
                                       : nlohmann::ordered_json{{"skipped", out.mura_skipped}};
        j["baselines"] = b;
    }
    if (!report.config_file.empty()) {
        j["report"] = report.report_files;
        j["config"] = report.config_file;
    }
    return j;
}

std::filesystem::path compare_config_path(const std::filesystem::path& report_path) {
    std::filesystem::path config = report_path;
    config.replace_filename(config.stem().string() + ".config.json");
    return config;
}

void write_compare_report(CompareReport& report) {
    if (report.report_pages.empty()) return;
    StagedFiles files;
    std::vector<std::string> written;
    for (const auto& [path, bytes] : report.report_pages) {
        files.stage_bytes(path, bytes);
        written.push_back(path.string());
    }
    const std::filesystem::path config = compare_config_path(report.request.report);
    report.report_files = written;
    report.config_file = config.string();
    files.stage_bytes(config, compare_json(report).dump(2) + "\n");
    files.commit();
}

}  // namespace pinmask::io
