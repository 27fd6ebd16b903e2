// `pinmask compare`: masks side by side (metrics table on stdout or as JSON) and, with --report,
// a multi-page report (PDF, or SVG/PNG pages) with each mask's pictures. --baselines adds the
// median of random valid masks, the paper-like geometry and a MURA. The figures come from
// optimize/metrics/compare (the metric set of optimize/metrics/mask_metrics, as score prints it),
// the document from cli/outputs/compare_report, the drawing from report/report.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/analytic_setup.hpp"
#include "cli/options/depth_range_flags.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/outputs/compare_report.hpp"
#include "cli/outputs/progress.hpp"
#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_set.hpp"
#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "optimize/metrics/compare.hpp"
#include "report/report.hpp"

namespace pinmask::cli {
namespace {

using io::json_strict::finite_or_null;
namespace fs = std::filesystem;

struct Options {
    std::vector<std::string> masks;
    bool baselines = false;
    int baseline_count = 100;
    NoiseFlags noise;
    PriorFlags prior;
    // search's default re-rank scenes: one mask shows one simulated figure in both.
    std::string scenes = "letter-R,usaf,siemens-star";
    std::string nsr = "tuned";
    std::string tv_lambda = "1e-3";
    std::string robust;
    int tv_iterations = 200;
    std::uint64_t seed = 1;
    bool depth = false;
    double depth_from = 0, depth_to = 0;
    bool allow_violations = false, json = false, quiet = false;
    std::string report;
};

CompareRunOptions make_options(const Options& o, const CLI::App& cmd, std::string& noise) {
    CompareRunOptions r;
    MaskMetricsOptions& m = r.settings.metrics;
    m.tv = true;
    m.noise = noise_levels(o.noise, cmd, &noise);
    m.prior = prior_spec(o.prior);
    m.scenes = scene_specs(o.scenes);
    m.simulation.seed = o.seed;
    set_decoder_settings(m.simulation, o.nsr, o.tv_lambda, o.tv_iterations);
    if (!o.robust.empty()) m.robust = parse_fabrication_errors(o.robust);
    m.depth = o.depth;
    m.depth_range = depth_range_of(cmd, o.depth_from, o.depth_to, o.depth, "add --depth");
    r.settings.seed = o.seed;
    r.baselines = o.baselines;
    r.baseline_count = o.baseline_count;
    r.validate();
    return r;
}

void run(const Options& o, const CLI::App& cmd) {
    std::string noise;
    const CompareRunOptions options = make_options(o, cmd, noise);
    if (!o.report.empty()) {
        report_format(o.report, "--report");
        const fs::path dir = fs::path(o.report).parent_path();
        if (!dir.empty() && !fs::is_directory(dir))
            throw invalid_field("--report", o.report, "the output directory does not exist");
    }
    {
        std::vector<NamedPath> inputs;
        for (const std::string& m : o.masks) inputs.push_back({"masks", m});
        fs::path config = o.report;  // the report's pages are checked again as they are staged
        if (!o.report.empty()) config.replace_filename(config.stem().string() + ".config.json");
        plan_outputs(inputs, {{"--report", o.report}, {"--report (config)", config}});
    }
    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    std::vector<CompareEntry> entries;
    for (const std::string& path : o.masks) {
        CompareEntry e{fs::path(path).filename().string(), "input", path,
                       io::read_mask_file(path, ro)};
        if (!entries.empty()) require_same_camera(entries.front().mask, e.mask, path);
        entries.push_back(std::move(e));
    }
    CompareSummary summary;
    summary.camera = entries.front().mask.camera;
    summary.noise_text = noise;
    ProgressLine bar("pinmask compare");
    CompareOutcome out =
        run_compare(entries, options, [&](const std::string& phase, int done, int total) {
            if (o.quiet) return;
            if (total == 0) {  // a set-up phase
                bar.phase(phase);
            } else if (phase == "mask") {  // a mask starts: each named, also in a log
                bar.phase(
                    "mask " + std::to_string(done + 1) + "/" + std::to_string(total) + ": " +
                    (done < static_cast<int>(entries.size()) ? entries[done].name : "a baseline") +
                    " (metrics, simulated decodes)");
            } else {
                bar.update(double(done) / total,
                           phase + " " + std::to_string(done) + "/" + std::to_string(total));
            }
        });
    if (!o.quiet) bar.update(1.0, std::to_string(out.results.size()) + " masks compared");
    bar.finish();
    // The library's words name settings by field: spelled as flags (a given mask's source is
    // its path, left as typed).
    for (CompareResult& r : out.results)
        if (r.row.kind != "input") r.row.source = spell_flags(r.row.source);
    for (std::string& l : out.baseline_lines) l = spell_flags(l);
    out.random_skipped = spell_flags(out.random_skipped);
    out.mura_skipped = spell_flags(out.mura_skipped);
    summary.baseline_lines = out.baseline_lines;
    for (const auto& w : {out.random_skipped, out.mura_skipped})
        if (!w.empty()) std::cerr << "compare: warning: " << w << "\n";
    const MaskMetricsOptions& mo = options.settings.metrics;
    summary.settings_lines = {
        "Simulation: " + noise + ", scenes " + o.scenes +
        " (the first is shown on each page), Wiener NSR " + o.nsr + ", TV-L2 lambda " +
        o.tv_lambda + " (" + std::to_string(o.tv_iterations) + " iterations max), noise seed " +
        std::to_string(o.seed) + ". Analytic prior: " + mo.prior.description() + "." +
        (mo.robust.any() ? " Robust W: analytic Wiener expected under fabrication errors (" +
                               mo.robust.description() + "), decoded with the nominal PSF."
                         : "")};

    // What each PSNR column is computed on (the table's legend and the JSON's psnr_columns).
    const std::string nsr_words = o.nsr == "tuned" ? "NSR tuned per mask" : "NSR " + o.nsr;
    const std::string analytic_basis = "closed form over one period, prior " +
                                       mo.prior.description() + ", Wiener " + nsr_words + ", " +
                                       noise + " (first level)";
    const std::string sim_basis = "simulated on scenes " + o.scenes + " (cyclic model, " + noise +
                                  ", first level, noise seed " + std::to_string(o.seed) + ")";
    const std::string psnr_legend =
        "PSNR columns: analytic W = " + analytic_basis + "; sim W = " + sim_basis + ", Wiener " +
        nsr_words + "; sim TV = the same captures, TV-L2 lambda " + o.tv_lambda + ".\n";
    nlohmann::ordered_json j;
    for (const auto& r : out.results) j["masks"].push_back(compare_row_json(r.row));
    j["psnr_columns"] = {{"analytic_wiener_psnr_db", analytic_basis},
                         {"wiener_psnr_db", sim_basis + ", Wiener " + nsr_words},
                         {"tv_psnr_db", sim_basis + ", TV-L2 lambda " + o.tv_lambda}};
    nlohmann::ordered_json levels = nlohmann::ordered_json::array();
    for (const NoiseLevel& l : mo.noise) levels.push_back(noise_json(l.model));
    j["settings"] = {{"noise", levels},
                     {"scenes", o.scenes},
                     {"prior", mo.prior.description()},
                     {"wiener_nsr", o.nsr},
                     {"tv_lambda", o.tv_lambda},
                     {"tv_iterations", o.tv_iterations},
                     {"seed", o.seed},
                     {"baselines", o.baselines},
                     {"baseline_count", o.baseline_count},
                     {"robust", mo.robust.description()}};
    if (mo.depth) {
        j["settings"]["depth_from_m"] = o.depth_from;  // 0: the working distance / 2
        j["settings"]["depth_to_m"] = o.depth_to;      // 0: twice the working distance
    }
    if (o.baselines) {
        nlohmann::ordered_json b;
        if (out.random) {
            b["random"] = {{"count", out.random->count},
                           {"first_seed", o.seed},
                           {"median_seed", out.random->median_seed},
                           {"min_wiener_psnr_db", out.random->min_psnr_db},
                           {"median_wiener_psnr_db", out.random->median_psnr_db},
                           {"max_wiener_psnr_db", out.random->max_psnr_db}};
        } else {
            b["random"] = {{"skipped", out.random_skipped}};
        }
        b["paper_like"] = {{"seed", o.seed}};
        b["mura"] = out.mura_order > 0 ? nlohmann::ordered_json{{"order", out.mura_order}}
                                       : nlohmann::ordered_json{{"skipped", out.mura_skipped}};
        j["baselines"] = b;
    }
    std::vector<std::string> written;
    if (!o.report.empty()) {
        const ReportDocument doc = compare_document(out.results, options.settings, summary);
        StagedFiles files;
        for (const auto& [path, bytes] : render_report(doc, o.report)) {
            files.stage_bytes(path, bytes);
            written.push_back(path.string());
        }
        fs::path config = o.report;
        config.replace_filename(config.stem().string() + ".config.json");
        j["report"] = written;
        j["config"] = config.string();
        files.stage_bytes(config, j.dump(2) + "\n");
        files.commit();
    }
    if (o.json) {
        std::cout << j.dump(2) << "\n";
        return;
    }
    const std::string depth_legend =
        mo.depth ? "depth columns: the worst Cramer-Rao bound on a point source's distance over " +
                       std::string(o.depth_from > 0 ? "--depth-from .. --depth-to"
                                                    : "the working distance / 2 .. x 2") +
                       " (first level): sigma_u / u and the axial FWHM 2.355 sigma_u (score "
                       "--metrics depth).\n"
                 : "";
    std::cout << compare_table_text(compare_table(out.results)) << psnr_legend << depth_legend
              << compare_holes_text(out.results);
    for (const auto& r : out.results) {
        if (r.row.metrics.spectral_zero->found)
            std::cout << "warning: " << r.row.name << ": " << r.row.metrics.spectral_zero->message()
                      << "\n";
    }
    if (!written.empty()) {
        std::cout << "wrote " << written.size() << " report file(s): " << written.front()
                  << (written.size() > 1 ? " ..." : "") << " and " << j["config"].get<std::string>()
                  << "\n";
    }
}

void setup(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand(
        "compare",
        "Compare masks side by side: metrics table, optional baselines, and a multi-page report "
        "with each mask's pattern, PSF, log |OTF|, autocorrelation, a simulated capture and its "
        "Wiener and TV reconstructions.");
    cmd->footer(std::string(kCompareFooter) + "\n" + kRobustFooter);
    cmd->add_option("masks", o->masks, "Mask files (*.mask.json); the first sets the camera")
        ->required();
    cmd->add_flag("--baselines", o->baselines,
                  "Add the random-median, paper-like and MURA baselines (see below)");
    cmd->add_option("--baseline-count", o->baseline_count,
                    "Random valid masks drawn for the random-median baseline (1..10000)")
        ->capture_default_str();
    add_noise_flags(*cmd, o->noise, "30");
    add_prior_flags(*cmd, o->prior);
    cmd->add_option("--scenes", o->scenes,
                    "Scenes for simulated figures, comma-separated: letter-R, usaf, siemens-star, "
                    "checker, point, natural, or image files; the first is shown in the report")
        ->capture_default_str();
    cmd->add_option("--nsr", o->nsr,
                    "Wiener NSR (> 0) of the simulated and analytic figures, or 'tuned' per mask")
        ->capture_default_str();
    cmd->add_option("--robust", o->robust, kRobustFlagHelp);
    cmd->add_option("--tv-lambda", o->tv_lambda, "Simulated TV-L2 weight (> 0), or 'tuned' (slow)")
        ->capture_default_str();
    cmd->add_option("--tv-iters", o->tv_iterations, "TV-L2 maximum ADMM iterations (>= 1)")
        ->capture_default_str();
    cmd->add_flag("--depth", o->depth,
                  "Add the depth columns: score --metrics depth's Cramer-Rao bound on a point "
                  "source's distance (needs --photons)");
    add_depth_range_flags(*cmd, o->depth_from, o->depth_to, "--depth");
    cmd->add_option("--seed", o->seed, "Seed of the noise and of the baselines' random draws")
        ->capture_default_str();
    cmd->add_flag("--allow-violations", o->allow_violations,
                  "Read masks that break their spacing rule even when the file does not record "
                  "that violations were allowed");
    cmd->add_option("--report", o->report,
                    "Report file: .pdf (one file) or .svg/.png (one file per page, name-1.svg "
                    "...), plus name.config.json");
    cmd->add_flag("--json", o->json,
                  "Print {masks: [...], settings, baselines, report} as JSON on stdout");
    cmd->add_flag("--quiet", o->quiet, "No progress lines on stderr");
    cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace

void add_compare(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
