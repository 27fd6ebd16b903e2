#include <iostream>
#include <string>
#include <vector>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/analytic_setup.hpp"
#include "cli/options/depth_range_flags.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/options/number_lists.hpp"
#include "cli/outputs/robust_decoder_files.hpp"
#include "io/mask_json.hpp"
#include "io/score_json.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/score_run.hpp"

namespace pinmask::cli {
namespace {

struct ScoreOptions {
    std::vector<std::string> masks;
    std::string scenes = joined(ScoreRequest{}.scenes);
    NoiseFlags noise;
    PriorFlags prior;
    std::string metrics = joined(ScoreRequest{}.metrics);
    std::string nsr = ScoreRequest{}.wiener_nsr;
    std::string tv_lambda = ScoreRequest{}.tv_lambda;
    std::string robust, robust_decoder;
    int tv_iterations = ScoreRequest{}.tv_iterations;
    double depth_from = 0, depth_to = 0;
    int seeds = ScoreRequest{}.noise_seeds;
    std::uint64_t seed = ScoreRequest{}.seed;
    bool allow_violations = false, json = false, explain = false, quiet = false;
};

ScoreRequest make_request(const ScoreOptions& o, const CLI::App& cmd) {
    ScoreRequest q;
    q.metrics = split_list(o.metrics, "--metrics");
    MaskMetricsOptions chosen;
    select_metrics(chosen, q.metrics);
    q.noise = noise_levels(o.noise, cmd, &q.noise_text);
    q.prior = prior_spec(o.prior);
    q.scenes = split_list(o.scenes, "--scenes");
    q.noise_seeds = o.seeds;
    q.seed = o.seed;
    q.wiener_nsr = o.nsr;
    q.tv_lambda = o.tv_lambda;
    q.tv_iterations = o.tv_iterations;
    if (!o.robust.empty()) q.robust = o.robust;
    const DepthRange range =
        depth_range_of(cmd, o.depth_from, o.depth_to, chosen.depth, "add depth to --metrics");
    q.depth_from_m = range.from_m;
    q.depth_to_m = range.to_m;
    q.explain = o.explain;
    return q;
}

void run(const ScoreOptions& o, const CLI::App& cmd) {
    ScoreRequest q = make_request(o, cmd);
    const MaskMetricsOptions m = q.options();
    if (!o.robust_decoder.empty() || cmd.get_option("--robust-decoder")->count() > 0)
        check_robust_decoder_request(o.robust_decoder, o.masks, m.noise.size());
    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    for (const std::string& path : o.masks) q.masks.push_back(io::read_mask_file(path, ro));
    const Mask first = q.masks.front();  // --robust-decoder's one mask
    q.names = o.masks;
    q.progress = [&](std::size_t i, std::size_t count) {
        if (!o.quiet && !o.json && (m.tv || count > 1))
            std::cerr << "score: " << i + 1 << "/" << count << " " << o.masks[i]
                      << (m.tv ? " (TV decodes)" : "") << "\n";
    };
    ScoreReport r = run_score_request(std::move(q));
    for (std::string& line : r.explain) line = spell_flags(line);
    std::vector<nlohmann::ordered_json> rows;
    std::string usage;  // --robust-decoder: how to decode with it
    for (const ScoreRow& row : r.rows) {
        rows.push_back(io::score_row_json(row));
        if (o.robust_decoder.empty()) continue;
        const RobustDecoderFiles f = write_robust_decoder_files(
            o.robust_decoder, first, row.name, m.robust, r.context->prior(row.metrics.period_px),
            m.noise.front().model);
        rows.back()["robust_decoder"] = {{"psf", f.psf_tiff},
                                         {"psf_npy", f.psf_npy},
                                         {"nsr_map", f.nsr_npy},
                                         {"floored", f.floored}};
        if (!o.json) usage = robust_decoder_usage(f, row.name);
    }
    if (o.explain) {
        for (const auto& line : r.explain) std::cerr << "explain: " << line << "\n";
    }
    if (!o.json) return void(std::cout << metrics_table_text(rows, m) << usage);
    std::cout << io::score_json(r, rows, o.explain).dump(2) << "\n";
}

void setup(CLI::App& app) {
    auto o = std::make_shared<ScoreOptions>();
    auto* cmd = app.add_subcommand(
        "score",
        "Score masks: sidelobes, spectrum, analytic and simulated error; one row per mask.");
    cmd->footer(std::string(kScoreFooter) + "\n" + kRobustFooter);
    cmd->add_option("masks", o->masks, "Mask files (*.mask.json)")->required();
    cmd->add_option("--scenes", o->scenes,
                    "Scenes for simulated metrics, comma-separated: letter-R, usaf, "
                    "siemens-star, checker, point, natural, or image files (PNG/TIFF/npy)")
        ->capture_default_str();
    add_noise_flags(*cmd, o->noise, joined(ScoreRequest::kDefaultSnrDb));
    add_prior_flags(*cmd, o->prior);
    cmd->add_option("--metrics", o->metrics,
                    "Metrics to compute: sidelobes, spectrum, analytic, wiener, tv, depth (see "
                    "below; depth needs --photons)")
        ->capture_default_str();
    add_depth_range_flags(*cmd, o->depth_from, o->depth_to, "--metrics depth");
    cmd->add_option("--nsr", o->nsr,
                    "Wiener noise-to-signal ratio (> 0), or 'tuned' (per mask and noise level)")
        ->capture_default_str();
    auto* robust = cmd->add_option("--robust", o->robust, kRobustFlagHelp);
    cmd->add_option("--robust-decoder", o->robust_decoder,
                    "With --robust, one mask and one noise level: write DIR/robust-psf.tiff "
                    "(+ .npy, .json) and DIR/robust-nsr.npy, the decoder minimising the expected "
                    "fabricated error, for decode --psf ... --nsr-map ...")
        ->needs(robust);
    cmd->add_option("--tv-lambda", o->tv_lambda, "TV-L2 weight (> 0), or 'tuned'")
        ->capture_default_str();
    cmd->add_option("--tv-iters", o->tv_iterations, "TV-L2 maximum ADMM iterations (>= 1)")
        ->capture_default_str();
    cmd->add_option("--seeds", o->seeds,
                    "Noise realisations per scene and level for simulated metrics (1..1000); "
                    "the natural scene is always the texture of seed 0")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Base seed of the noise generators")->capture_default_str();
    cmd->add_flag("--allow-violations", o->allow_violations,
                  "Score masks that break their spacing rule even when the file does not "
                  "record that violations were allowed");
    cmd->add_flag("--json", o->json, "Print {masks: [...], settings, explain} as JSON on stdout");
    cmd->add_flag("--explain", o->explain,
                  "List on stderr (and under \"explain\" in --json) what was run, what was "
                  "skipped and why");
    cmd->add_flag("--quiet", o->quiet, "No progress lines on stderr");
    cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace

void add_score(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
