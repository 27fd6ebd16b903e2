#include "io/compare_json.hpp"

#include "core/files/atomic_file.hpp"
#include "io/json_strict.hpp"
#include "io/metrics_json.hpp"
#include "io/noise_json.hpp"
#include "optimize/metrics/paired_difference.hpp"

namespace pinmask::io {

using json_strict::finite_or_null;

namespace {

// {difference_db, standard_error_db, samples (paired), exact, significant}.
nlohmann::ordered_json difference_json(const PairedDifference& d) {
    nlohmann::ordered_json j{{"difference_db", finite_or_null(d.difference)}};
    if (d.exact) {
        j["standard_error_db"] = 0.0;
        j["exact"] = true;
    } else {
        j["standard_error_db"] = finite_or_null(d.standard_error);
        j["samples"] = d.samples;
        j["exact"] = false;
    }
    j["significant"] = d.significant;
    return j;
}

}  // namespace

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
                             {"analytic_mmse_psnr_db", finite_or_null(r.analytic_mmse_psnr_db)},
                             {"analytic_wiener_psnr_db", finite_or_null(r.analytic_wiener_psnr_db)},
                             {"analytic_wiener_nsr", r.analytic_wiener_nsr},
                             {"sim_wiener_psnr_db", finite_or_null(r.sim_wiener_psnr_db)},
                             {"sim_wiener_ssim", finite_or_null(r.sim_wiener_ssim)},
                             {"sim_wiener_nsr", r.sim_wiener_nsr},
                             {"sim_tv_psnr_db", finite_or_null(r.sim_tv_psnr_db)},
                             {"sim_tv_ssim", finite_or_null(r.sim_tv_ssim)},
                             {"sim_tv_lambda", r.sim_tv_lambda}};
    if (!r.to_first.empty()) {
        nlohmann::ordered_json d;
        for (const auto& [name, diff] : r.to_first) d[name] = difference_json(diff);
        j["difference_to_first"] = d;
    }
    metrics_json(r.metrics, j);  // every level with score's keys
    return j;
}

nlohmann::ordered_json compare_json(const CompareReport& report) {
    const CompareRequest& q = report.request;
    const CompareOutcome& out = report.outcome;
    const MaskMetricsOptions& mo = report.options.settings.metrics;
    nlohmann::ordered_json j;
    for (const auto& r : out.results) j["masks"].push_back(compare_row_json(r.row));
    j["lead_figure"] = {{"name", out.lead.name}, {"reason", out.lead.reason}};
    if (!out.lead_mismatch.empty()) j["lead_figure"]["mismatch"] = out.lead_mismatch;
    j["psnr_columns"] = {
        {"analytic_mmse_psnr_db", report.mmse_basis},
        {"analytic_wiener_psnr_db", report.analytic_basis},
        {"sim_wiener_psnr_db", report.sim_basis + ", Wiener " + report.nsr_words},
        {"sim_tv_psnr_db", report.sim_basis + ", TV-L2 lambda " + q.tv_lambda},
        {"difference_to_first",
         "each mask minus the first: analytic figures exact (closed form), simulated ones paired "
         "over the scenes with the standard error of the mean difference; significant: exact and "
         "non-zero, or at least two standard errors"}};
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
            const std::string& f = out.random->figure;
            b["random"] = {{"count", out.random->count},
                           {"first_seed", q.seed},
                           {"median_seed", out.random->median_seed},
                           {"ranked_by", f},
                           {"min_" + f, out.random->min_psnr_db},
                           {"median_" + f, out.random->median_psnr_db},
                           {"median_standard_error_db", out.random->median_standard_error_db},
                           {"max_" + f, out.random->max_psnr_db}};
            if (out.random_gain) {
                nlohmann::ordered_json g = difference_json(*out.random_gain);
                g["text"] = report.random_gain_text;
                b["random"]["first_mask_gain"] = g;
            }
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
