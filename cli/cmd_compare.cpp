// `pinmask compare`: masks side by side (metrics table on stdout or as JSON) and, with --report,
// a multi-page report (PDF, or SVG/PNG pages) with each mask's pictures. --baselines adds the
// median of random valid masks, the paper-like geometry and a MURA. Parses the flags into
// report/compare_run's request, reads the masks, runs it, and prints the table
// (cli/outputs/compare_report) or io/compare_json's JSON, which it also writes beside the report.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/analytic_setup.hpp"
#include "cli/options/depth_range_flags.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/options/number_lists.hpp"
#include "cli/outputs/compare_report.hpp"
#include "cli/outputs/progress.hpp"
#include "core/files/output_set.hpp"
#include "io/compare_json.hpp"
#include "io/mask_json.hpp"
#include "report/compare_run.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
    std::vector<std::string> masks;
    bool baselines = false;
    int baseline_count = CompareRequest{}.baseline_count;
    NoiseFlags noise;
    PriorFlags prior;
    std::string scenes = joined(CompareRequest{}.scenes);
    std::string nsr = CompareRequest{}.wiener_nsr;
    std::string tv_lambda = CompareRequest{}.tv_lambda;
    std::string robust;
    int tv_iterations = CompareRequest{}.tv_iterations;
    std::uint64_t seed = CompareRequest{}.seed;
    bool depth = false;
    double depth_from = 0, depth_to = 0;
    bool allow_violations = false, json = false, quiet = false;
    std::string report;
};

CompareRequest make_request(const Options& o, const CLI::App& cmd) {
    CompareRequest q;
    q.noise = noise_levels(o.noise, cmd, &q.noise_text);
    q.prior = prior_spec(o.prior);
    q.scenes = split_list(o.scenes, "--scenes");
    q.wiener_nsr = o.nsr;
    q.tv_lambda = o.tv_lambda;
    q.tv_iterations = o.tv_iterations;
    q.seed = o.seed;
    if (!o.robust.empty()) q.robust = o.robust;
    q.depth = o.depth;
    const DepthRange range = depth_range_of(cmd, o.depth_from, o.depth_to, o.depth, "add --depth");
    q.depth_from_m = range.from_m;
    q.depth_to_m = range.to_m;
    q.baselines = o.baselines;
    q.baseline_count = o.baseline_count;
    q.report = o.report;
    q.spell = [](const std::string& s) { return spell_flags(s); };
    return q;
}

void run(const Options& o, const CLI::App& cmd) {
    CompareRequest request = make_request(o, cmd);
    request.validate();
    {
        std::vector<NamedPath> inputs;
        for (const std::string& m : o.masks) inputs.push_back({"masks", m});
        // the report's pages are checked again as they are staged
        const fs::path config = o.report.empty() ? fs::path() : io::compare_config_path(o.report);
        plan_outputs(inputs, {{"--report", o.report}, {"--report (config)", config}});
    }
    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    for (const std::string& path : o.masks) {
        CompareEntry e{fs::path(path).filename().string(), "input", path,
                       io::read_mask_file(path, ro)};
        if (!request.entries.empty())
            require_same_camera(request.entries.front().mask, e.mask, path);
        request.entries.push_back(std::move(e));
    }
    const std::vector<std::string> names = o.masks;
    ProgressLine bar("pinmask compare");
    CompareReport r =
        run_compare_request(std::move(request), [&](const std::string& phase, int done, int total) {
            if (o.quiet) return;
            if (total == 0) {  // a set-up phase
                bar.phase(phase);
            } else if (phase == "mask") {  // a mask starts: each named, also in a log
                bar.phase("mask " + std::to_string(done + 1) + "/" + std::to_string(total) + ": " +
                          (done < static_cast<int>(names.size())
                               ? fs::path(names[done]).filename().string()
                               : "a baseline") +
                          " (metrics, simulated decodes)");
            } else {
                bar.update(double(done) / total,
                           phase + " " + std::to_string(done) + "/" + std::to_string(total));
            }
        });
    if (!o.quiet) bar.update(1.0, std::to_string(r.outcome.results.size()) + " masks compared");
    bar.finish();
    for (const std::string& w : r.warnings) std::cerr << "compare: warning: " << w << "\n";
    io::write_compare_report(r);
    if (o.json) {
        std::cout << io::compare_json(r).dump(2) << "\n";
        return;
    }
    const bool depth = r.options.settings.metrics.depth;
    const std::string depth_legend =
        depth ? "depth columns: the worst Cramer-Rao bound on a point source's distance over " +
                    std::string(o.depth_from > 0 ? "--depth-from .. --depth-to"
                                                 : "the working distance / 2 .. x 2") +
                    " (first level): sigma_u / u and the axial FWHM 2.355 sigma_u (score "
                    "--metrics depth).\n"
              : "";
    const LeadFigure& lead = r.outcome.lead;
    std::cout << "Leading with " << lead.name << " (" << figure_words(lead.name)
              << "): " << lead.reason << ".\n"
              << compare_table_text(compare_table(r.outcome.results, lead.name))
              << "PSNR columns: analytic MMSE = " << r.mmse_basis
              << "; analytic W = " << r.analytic_basis << "; sim W = " << r.sim_basis << ", Wiener "
              << r.nsr_words << "; sim TV = the same captures, TV-L2 lambda " << o.tv_lambda
              << ". vs 1st: minus the first mask; analytic exact, simulated paired over the "
                 "scenes +- its standard error, n.s. under two.\n"
              << depth_legend << compare_holes_text(r.outcome.results);
    if (!r.random_gain_text.empty()) std::cout << r.random_gain_text << "\n";
    if (!r.outcome.lead_mismatch.empty()) std::cout << r.outcome.lead_mismatch << "\n";
    for (const auto& c : r.outcome.results) {
        if (c.row.metrics.spectral_zero->found)
            std::cout << "warning: " << c.row.name << ": " << c.row.metrics.spectral_zero->message()
                      << "\n";
    }
    if (!r.report_files.empty()) {
        std::cout << "wrote " << r.report_files.size()
                  << " report file(s): " << r.report_files.front()
                  << (r.report_files.size() > 1 ? " ..." : "") << " and " << r.config_file << "\n";
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
    add_noise_flags(*cmd, o->noise, joined(CompareRequest::kDefaultSnrDb));
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
