// `pinmask score`: metrics of one or more masks, one row per mask. Only what --metrics asks for
// is computed; the numerics are optimize/metrics/mask_metrics (the same set compare and search
// use); this file parses flags, calls it per mask, and prints.
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/analytic_setup.hpp"
#include "cli/options/depth_range_flags.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/outputs/robust_decoder_files.hpp"
#include "core/errors/error.hpp"
#include "io/mask_json.hpp"
#include "io/noise_json.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/metric_spellings.hpp"

namespace pinmask::cli {
namespace {

struct ScoreOptions {
    std::vector<std::string> masks;
    std::string scenes = "letter-R,usaf,natural";
    NoiseFlags noise;
    PriorFlags prior;
    std::string metrics = "sidelobes,spectrum,analytic,wiener";
    std::string nsr = "0.01";
    std::string tv_lambda = "1e-3";
    std::string robust, robust_decoder;
    int tv_iterations = 200;
    double depth_from = 0, depth_to = 0;
    int seeds = 1;
    std::uint64_t seed = 0;
    bool allow_violations = false, json = false, explain = false, quiet = false;
};

MaskMetricsOptions make_options(const ScoreOptions& o, const CLI::App& cmd, std::string& noise) {
    MaskMetricsOptions m;
    select_metrics(m, split_list(o.metrics, "--metrics"));
    m.noise = noise_levels(o.noise, cmd, &noise);
    m.prior = prior_spec(o.prior);
    m.scenes = scene_specs(o.scenes);
    m.simulation.noise_seeds = o.seeds;
    m.simulation.seed = o.seed;
    set_decoder_settings(m.simulation, o.nsr, o.tv_lambda, o.tv_iterations);
    if (!o.robust.empty()) m.robust = parse_fabrication_errors(o.robust);
    m.depth_range =
        depth_range_of(cmd, o.depth_from, o.depth_to, m.depth, "add depth to --metrics");
    m.validate();
    return m;
}

std::vector<std::string> explain_lines(const ScoreOptions& o, const MaskMetricsOptions& m,
                                       const std::string& noise) {
    std::vector<std::string> e;
    const auto line = [&](bool on, const std::string& name, const std::string& what) {
        e.push_back(name + ": " + (on ? what : "skipped (not in --metrics)"));
    };
    line(m.sidelobes, "sidelobes", "torus autocorrelation from the n x n pattern DFT");
    line(m.spectrum, "spectrum",
         "min |P^|, flatness, open fraction, light gain from the pattern DFT; OTF condition over "
         "the kernel passband |K^| >= 0.1 max |K^|; spectral zeros |P^| < 1e-3 sqrt(K) there");
    line(m.analytic, "analytic",
         "closed-form expected Wiener MSE over one period, " + noise + ", NSR " + o.nsr +
             ", plus the per-frequency optimal Wiener bound; prior " + m.prior.description());
    for (const auto& [on, name] :
         {std::pair{m.wiener, std::string("wiener")}, std::pair{m.tv, std::string("tv")}}) {
        line(on, name,
             "simulated one period (cyclic model: capture = scene (*) PSF, " + noise + "), " +
                 std::to_string(m.scenes.size()) + " scene(s) x " + std::to_string(o.seeds) +
                 " noise seed(s)");
    }
    if (m.robust.any()) {
        line(m.analytic, "robust",
             "the analytic figure expected under fabrication errors (" + m.robust.description() +
                 "), decoded with the nominal PSF: closed form, no sampling");
    }
    line(m.depth, "depth",
         "Cramer-Rao bound on the distance of a point source on the axis (exact-geometry PSF over "
         "the sensor, its derivative in 1/u, Poisson + read noise of the photon level), worst "
         "over " +
             std::to_string(kDepthSamples) + " distances equally spaced in 1/u");
    if (!m.tv) e.push_back("tv: add tv to --metrics to run TV-L2 decodes (slow)");
    if (!(m.wiener || m.tv)) e.push_back("scene rendering: skipped (no simulated metric)");
    e.push_back("full-sensor simulation: skipped (the cyclic model needs one period only)");
    return e;
}

void run(const ScoreOptions& o, const CLI::App& cmd) {
    std::string noise;
    MetricsContext context(make_options(o, cmd, noise));
    const MaskMetricsOptions& m = context.options();
    if (!o.robust_decoder.empty() || cmd.get_option("--robust-decoder")->count() > 0)
        check_robust_decoder_request(o.robust_decoder, o.masks, m.noise.size());
    std::vector<std::string> explain = explain_lines(o, m, noise);
    std::vector<nlohmann::ordered_json> rows;
    std::string usage;  // --robust-decoder: how to decode with it
    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    for (std::size_t i = 0; i < o.masks.size(); ++i) {
        const std::string& path = o.masks[i];
        if (!o.quiet && !o.json && (m.tv || o.masks.size() > 1)) {
            std::cerr << "score: " << i + 1 << "/" << o.masks.size() << " " << path
                      << (m.tv ? " (TV decodes)" : "") << "\n";
        }
        const Mask mask = io::read_mask_file(path, ro);
        const MaskMetrics mm = compute_mask_metrics(mask, context);
        nlohmann::ordered_json row;
        row["mask"] = path;
        row["geometry_hash"] = geometry_hash(mask);
        row["n"] = mm.n;
        row["holes"] = mm.holes;
        row["pixels_per_cell"] = mm.pixels_per_cell;
        row["period_px"] = mm.period_px;
        nlohmann::ordered_json per_scene = nlohmann::ordered_json::object();
        metrics_json(mm, row, &per_scene);
        if (!per_scene.empty()) row["per_scene"] = per_scene;
        if (!mm.kernel_description.empty())
            explain.push_back("kernel of " + path + ": " + mm.kernel_description);
        if (m.analytic && o.explain) {
            const PriorRelevance pr = prior_relevance(context.prior(mm.period_px));
            explain.push_back(
                "prior at " + std::to_string(mm.period_px) +
                " px: " + std::to_string(pr.irrelevant) + " of " + std::to_string(pr.total) +
                " frequencies carry < 1e-6 of its peak power (irrelevant to the analytic error; "
                "still summed, nothing skipped); relevant up to radius " +
                std::to_string(pr.highest_relevant_radius) + " cycles per period");
        }
        if (!o.robust_decoder.empty()) {
            const RobustDecoderFiles f =
                write_robust_decoder_files(o.robust_decoder, mask, path, m.robust,
                                           context.prior(mm.period_px), m.noise.front().model);
            row["robust_decoder"] = {{"psf", f.psf_tiff},
                                     {"psf_npy", f.psf_npy},
                                     {"nsr_map", f.nsr_npy},
                                     {"floored", f.floored}};
            if (!o.json) usage = robust_decoder_usage(f, path);
        }
        rows.push_back(std::move(row));
    }
    if (o.explain) {
        for (const auto& line : explain) std::cerr << "explain: " << line << "\n";
    }
    if (!o.json) return void(std::cout << metrics_table_text(rows, m) << usage);
    nlohmann::ordered_json j;
    j["masks"] = rows;
    nlohmann::ordered_json levels = nlohmann::ordered_json::array();
    for (const NoiseLevel& level : m.noise) {
        nlohmann::ordered_json l = io::noise_json(level.model);
        l["key"] = level.key;
        levels.push_back(l);
    }
    j["settings"] = {{"metrics", o.metrics},
                     {"scenes", o.scenes},
                     {"noise", levels},
                     {"prior", m.prior.description()},
                     {"nsr", o.nsr},
                     {"tv_lambda", o.tv_lambda},
                     {"seeds", o.seeds},
                     {"seed", o.seed},
                     {"tv_iterations", o.tv_iterations},
                     {"robust", m.robust.description()}};
    if (m.depth) {
        j["settings"]["depth_from_m"] = o.depth_from;  // 0: the working distance / 2
        j["settings"]["depth_to_m"] = o.depth_to;      // 0: twice the working distance
    }
    if (o.noise.photons.empty()) {
        std::vector<double> snrs;
        for (const NoiseLevel& level : m.noise) snrs.push_back(level.model.snr_db);
        j["settings"]["snr_db"] = snrs;
    }
    if (o.explain) j["explain"] = explain;
    std::cout << j.dump(2) << "\n";
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
    add_noise_flags(*cmd, o->noise, "20,30,40");
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
