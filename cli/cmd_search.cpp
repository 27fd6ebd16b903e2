// `pinmask search`: find masks for a camera that decode better than random draws.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/analytic_setup.hpp"
#include "cli/camera_options.hpp"
#include "cli/command.hpp"
#include "cli/interrupt.hpp"
#include "io/optics_json.hpp"
#include "cli/progress.hpp"
#include "cli/psf_options.hpp"
#include "io/search_config.hpp"
#include "cli/search_outputs.hpp"
#include "core/error.hpp"
#include "core/fft.hpp"
#include "core/output_set.hpp"
#include "core/units.hpp"
#include "design/psf.hpp"
#include "design/random_sparse.hpp"
#include "optimize/mask_objective.hpp"
#include "optimize/scene_prior.hpp"
#include "optimize/scenes.hpp"
#include "optimize/simulated_metrics.hpp"

namespace pinmask::cli {
namespace {

constexpr const char* kGenerator = "pinmask search 0.1.0";

struct Options {
    CameraOptions camera;
    GeometryOptions geometry;
    PsfOptions psf;
    std::string strategy = "anneal";
    std::string time = "20s";
    std::int64_t evals = 0;
    int threads = 0;
    std::uint64_t seed = 1;
    int top = 5;
    double snr_db = 30.0;
    std::string filter = "optimal";
    double w_analytic = 1.0, w_max_sidelobe = 0.0, w_sidelobe_energy = 0.0, w_min_spectrum = 0.0;
    int prior_scenes = kDefaultPriorScenes;
    std::string keep_out = "none";
    std::vector<std::string> rerank_scenes{"letter-R", "usaf", "siemens-star"};
    bool rerank_tv = true;
    bool no_rerank = false;
    std::string output;
    bool json = false;
    std::string config;  // --config FILE
};

// The settings of --config FILE, for every option the command line did not give.
void apply_config(const io::SearchConfig& c, const CLI::App& cmd, Options& o) {
    auto given = [&](const char* flag) { return cmd.get_option(flag)->count() > 0; };
    auto set = [&](const char* flag, auto& field, const auto& value) {
        if (value && !given(flag)) field = *value;
    };
    set("--strategy", o.strategy, c.strategy);
    set("--time", o.time, c.time);
    // A --time on the command line replaces the file's evaluation budget (and --evals its time).
    if (!given("--time")) set("--evals", o.evals, c.evaluations_per_chain);
    set("--threads", o.threads, c.threads);
    set("--seed", o.seed, c.seed);
    set("--top", o.top, c.top);
    set("--grid", o.geometry.grid, c.grid);
    set("--holes", o.geometry.holes, c.holes);
    set("--tiles", o.geometry.tiles, c.tiles);
    set("--spacing", o.geometry.spacing, c.min_spacing_cells);
    set("--keep-out", o.keep_out, c.keep_out);
    set("--pixels-per-cell", o.psf.pixels_per_cell, c.pixels_per_cell);
    set("--kernel", o.psf.kernel, c.kernel);
    set("--kernel-path", o.psf.kernel_path, c.kernel_path);
    set("--snr", o.snr_db, c.snr_db);
    set("--filter", o.filter, c.filter);
    set("--prior-scenes", o.prior_scenes, c.prior_scenes);
    set("--w-analytic", o.w_analytic, c.w_analytic);
    set("--w-max-sidelobe", o.w_max_sidelobe, c.w_max_sidelobe);
    set("--w-sidelobe-energy", o.w_sidelobe_energy, c.w_sidelobe_energy);
    set("--w-min-spectrum", o.w_min_spectrum, c.w_min_spectrum);
    if (c.rerank_scenes && !given("--rerank-scenes") && !given("--no-rerank")) {
        if (c.rerank_scenes->empty())
            o.no_rerank = true;  // written for a run with --no-rerank
        else
            o.rerank_scenes = *c.rerank_scenes;
    }
    set("--no-rerank-tv", o.rerank_tv, c.rerank_tv);
    // The file's camera replaces the preset unless --preset is given; single camera flags still
    // override its fields.
    if (c.optics && !given("--preset")) o.camera.base = c.optics;
}

std::vector<Cell> keep_out_cells(const std::string& spec, int n) {
    std::vector<Cell> cells;
    if (spec == "none") return cells;
    if (spec == "border") {
        for (int i = 0; i < n; ++i) {
            cells.push_back({0, i});
            if (n > 1) cells.push_back({n - 1, i});
            if (i > 0 && i < n - 1) {
                cells.push_back({i, 0});
                cells.push_back({i, n - 1});
            }
        }
        return cells;
    }
    throw invalid_field("--keep-out", spec, "expected none or border");
}

// A random valid pattern avoiding keep-out cells: the random family, then each pinhole that sits
// in a keep-out cell moved to a random legal cell outside it.
Pattern sample_pattern(const RandomSparseOptions& ro, const std::vector<Cell>& keep_out,
                       std::mt19937_64& rng) {
    Pattern p = random_sparse_pattern(ro, rng);
    if (keep_out.empty()) return p;
    PatternState s(p);
    auto blocked = [&](Cell c) {
        return std::find(keep_out.begin(), keep_out.end(), c) != keep_out.end();
    };
    std::uniform_int_distribution<int> cell(0, ro.n - 1);
    for (int j = 0; j < s.holes(); ++j) {
        if (!blocked(s.pattern().pinholes[static_cast<std::size_t>(j)])) continue;
        bool moved = false;
        for (int attempt = 0; attempt < 100000 && !moved; ++attempt) {
            const Cell to{cell(rng), cell(rng)};
            if (!blocked(to) && s.is_legal_move(j, to)) {
                s.move(j, to);
                moved = true;
            }
        }
        if (!moved) {
            throw invalid_field("--keep-out", "border",
                                "no legal cell left outside the keep-out area for " +
                                    std::to_string(ro.holes) + " pinholes");
        }
    }
    return s.pattern();
}

std::vector<NamedScene> held_out_scenes(const std::vector<std::string>& names, int m) {
    std::vector<NamedScene> scenes;
    for (const auto& name : names) {
        if (name == "natural") {
            throw invalid_field("--rerank-scenes", name,
                                "the search prior is built from natural scenes; re-ranking must "
                                "use scenes the search did not see");
        }
        scenes.push_back({name, make_scene(scene_from_name(name), m, m)});
    }
    return scenes;
}

nlohmann::ordered_json resolved_config(const Options& o, const Mask& tmpl, const Kernel& kernel,
                                       int threads) {
    return {{"format", io::kSearchConfigFormat},
            {"version", io::kSearchConfigVersion},
            {"generator", kGenerator},
            {"strategy", o.strategy},
            {"time", o.time},
            {"evaluations_per_chain", o.evals},
            {"threads", threads},
            {"seed", o.seed},
            {"top", o.top},
            {"grid", tmpl.pattern.n},
            {"holes", o.geometry.holes},
            {"tiles", tmpl.pattern.tiles_rows},
            {"min_spacing_cells", tmpl.pattern.min_spacing_cells},
            {"keep_out", o.keep_out},
            {"pixels_per_cell", tmpl.psf.pixels_per_cell},
            {"kernel_requested", tmpl.psf.kernel.model},
            {"kernel_resolved", kernel_model_name(kernel.model)},
            {"kernel_path", tmpl.psf.kernel.measured_path},
            {"noise", {{"model", "gaussian"}, {"snr_db", o.snr_db}}},
            {"filter", o.filter},
            {"prior", {{"family", "natural"}, {"scenes", o.prior_scenes}}},
            {"weights",
             {{"analytic_wiener", o.w_analytic},
              {"max_sidelobe", o.w_max_sidelobe},
              {"sidelobe_energy", o.w_sidelobe_energy},
              {"min_spectrum", o.w_min_spectrum}}},
            {"rerank_scenes", o.no_rerank ? std::vector<std::string>{} : o.rerank_scenes},
            {"rerank_tv", !o.no_rerank && o.rerank_tv},
            {"optics", io::optics_to_json<nlohmann::ordered_json>(tmpl.camera)}};
}

void run(const Options& o) {
    const Camera camera = resolve_camera(o.camera);
    Mask tmpl;
    tmpl.camera = camera;
    tmpl.psf = resolve_psf_spec(o.psf, camera);
    tmpl.pattern.n = o.geometry.grid;
    tmpl.pattern.tiles_rows = tmpl.pattern.tiles_cols = o.geometry.tiles;
    tmpl.pattern.min_spacing_cells = o.geometry.spacing;
    validate(tmpl.pattern);
    if (o.geometry.holes < 1) {
        throw invalid_field("--holes", std::to_string(o.geometry.holes), "must be >= 1");
    }
    SearchOptions so;
    so.strategy = o.strategy == "random" ? SearchStrategy::kRandom : SearchStrategy::kAnneal;
    so.threads = o.threads > 0 ? o.threads
                               : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    so.time_budget_s = o.evals > 0 ? 0.0 : parse_duration_s(o.time, "--time");
    so.max_evaluations = o.evals;
    so.seed = o.seed;
    so.top = o.top;
    so.keep_out = keep_out_cells(o.keep_out, tmpl.pattern.n);
    so.validate();
    const WienerFilterSpec filter = parse_wiener_filter(o.filter);
    ObjectiveWeights weights{o.w_analytic, o.w_max_sidelobe, o.w_sidelobe_energy, o.w_min_spectrum};
    weights.validate();
    if (o.output.empty()) throw InvalidInput("-o/--output: an output folder is required");
    {
        const std::filesystem::path dir = o.output;  // rank-N.mask.json are checked when staged
        plan_outputs({{"--config", o.config}}, {{"-o (run log)", dir / "run-log.csv", true},
                                                {"-o (summary)", dir / "summary.md", true},
                                                {"-o (config)", dir / "search.config.json", true}});
    }

    const int n = tmpl.pattern.n, ppc = tmpl.psf.pixels_per_cell, m = n * ppc;
    check_psf_memory(n, ppc, 4, 2);
    const Kernel kernel = mask_kernel(tmpl);
    std::shared_ptr<const AnalyticWienerModel> model;
    if (weights.analytic_wiener > 0.0) {
        model = std::make_shared<AnalyticWienerModel>(
            analytic_wiener_model(kernel, n, ppc, o.snr_db, o.prior_scenes));
    }
    const MaskObjective objective(weights, model, filter);
    RandomSparseOptions ro;
    ro.n = n;
    ro.holes = o.geometry.holes;
    ro.min_spacing_cells = o.geometry.spacing;
    ro.tiles_rows = ro.tiles_cols = o.geometry.tiles;
    {
        std::mt19937_64 probe(o.seed);  // fail fast on infeasible requests, before threads start
        sample_pattern(ro, so.keep_out, probe);
    }
    const std::vector<NamedScene> scenes =
        o.no_rerank ? std::vector<NamedScene>{} : held_out_scenes(o.rerank_scenes, m);

    ProgressLine bar;
    const auto& interrupted = install_interrupt_flag();
    const SearchSummary summary = run_search(
        objective, so, [&](std::mt19937_64& rng) { return sample_pattern(ro, so.keep_out, rng); },
        &interrupted,
        [&](const SearchLogRow& row, double fraction) {
            char text[128];
            std::snprintf(text, sizeof text, "best %.4f, %.3g evals/s, %.0f s", row.best_objective,
                          row.seconds > 0 ? row.evaluations / row.seconds : 0.0, row.seconds);
            bar.update(fraction, text);
        });
    bar.finish();
    if (summary.ranked.empty()) throw RuntimeFailure("search stopped before any evaluation");
    if (summary.stop_reason == "interrupted") {
        std::cerr << "pinmask search: interrupted; writing the best " << summary.ranked.size()
                  << " candidate(s) found so far\n";
    }

    std::vector<RankedMask> ranked;
    SimulatedMetricsOptions sim;
    sim.seed = o.seed;
    sim.wiener_nsr = {true, 0.01};
    for (const Candidate& c : summary.ranked) {
        RankedMask r;
        r.mask = tmpl;
        r.mask.pattern = c.pattern;
        r.mask.pattern.pinholes = sorted_pinholes(c.pattern);
        r.mask.provenance.seed = o.seed;
        r.mask.provenance.generator = kGenerator;
        r.mask.provenance.family = "search:" + o.strategy;
        r.mask.provenance.scores = c.terms;
        r.objective = c.objective;
        r.sim_wiener_psnr_db = r.sim_tv_psnr_db = NAN;
        if (!scenes.empty() && !interrupted.load()) {
            const Plane psf = mask_psf(r.mask);
            r.sim_wiener_psnr_db =
                simulated_quality(psf, scenes, o.snr_db, SimulatedDecoder::kWiener, sim)
                    .mean_psnr_db;
            r.mask.provenance.scores["sim_wiener_psnr_db"] = r.sim_wiener_psnr_db;
            if (o.rerank_tv) {
                r.sim_tv_psnr_db =
                    simulated_quality(psf, scenes, o.snr_db, SimulatedDecoder::kTv, sim)
                        .mean_psnr_db;
                r.mask.provenance.scores["sim_tv_psnr_db"] = r.sim_tv_psnr_db;
            }
        }
        ranked.push_back(std::move(r));
    }
    if (!scenes.empty() && !interrupted.load()) {
        // Final stage: simulated reconstruction on held-out scenes decides the order.
        std::stable_sort(ranked.begin(), ranked.end(),
                         [](const RankedMask& a, const RankedMask& b) {
                             return a.sim_wiener_psnr_db > b.sim_wiener_psnr_db;
                         });
    }
    const auto paths = write_search_outputs(o.output, ranked, summary,
                                            resolved_config(o, tmpl, kernel, so.threads));
    if (o.json) {
        nlohmann::ordered_json j{{"output", o.output},
                                 {"evaluations", summary.evaluations},
                                 {"evaluations_per_chain", summary.evaluations_per_chain},
                                 {"seconds", summary.seconds},
                                 {"stop_reason", summary.stop_reason}};
        for (std::size_t i = 0; i < ranked.size(); ++i) {
            nlohmann::ordered_json r{{"rank", i + 1},
                                     {"path", paths[i].string()},
                                     {"geometry_hash", geometry_hash(ranked[i].mask)},
                                     {"objective", ranked[i].objective}};
            for (const auto& [k, v] : ranked[i].mask.provenance.scores) r[k] = v;
            j["ranked"].push_back(r);
        }
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << search_summary_markdown(ranked, summary) << "wrote " << paths.size()
                  << " masks, run-log.csv, summary.md and search.config.json to " << o.output
                  << "\n";
    }
}

const Registration kSearch(50, "search", [](CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand(
        "search",
        "Search random sparse cyclic patterns under the spacing rule for the mask that decodes "
        "best. The objective is the analytic expected Wiener PSNR (closed form from the OTF, a "
        "natural-scene prior and Gaussian noise at --snr) plus optional sidelobe and spectrum "
        "terms; the top candidates are then re-ranked by simulated Wiener (and TV) "
        "reconstruction of scenes the search did not see.");
    add_camera_options(*cmd, o->camera);
    add_geometry_options(*cmd, o->geometry);
    add_psf_options(*cmd, o->psf);
    cmd->add_option("--strategy", o->strategy,
                    "random: sample valid patterns, keep the best (the paper's approach, the "
                    "baseline); anneal: simulated annealing moving one pinhole at a time")
        ->check(CLI::IsMember({"random", "anneal"}))
        ->capture_default_str();
    cmd->add_option("--time", o->time, "Wall-clock budget (e.g. 20s, 2min)")->capture_default_str();
    cmd->add_option("--evals", o->evals,
                    "Evaluation budget per chain instead of --time: same seed and thread count "
                    "give identical results (with --time the work done depends on the machine)");
    cmd->add_option("--threads", o->threads, "Independent chains (default: all cores)");
    cmd->add_option("--seed", o->seed, "Seed of every chain's generator")->capture_default_str();
    cmd->add_option("--top", o->top, "Candidates to keep and write")->capture_default_str();
    cmd->add_option("--snr", o->snr_db, "Gaussian noise level of the objective, dB")
        ->capture_default_str();
    cmd->add_option("--filter", o->filter,
                    "Wiener filter the analytic error assumes: optimal (per-frequency) or "
                    "nsr:VALUE (deconvwnr's fixed NSR)")
        ->capture_default_str();
    cmd->add_option("--w-analytic", o->w_analytic, "Weight of -analytic Wiener PSNR (dB)")
        ->capture_default_str();
    cmd->add_option("--w-max-sidelobe", o->w_max_sidelobe, "Weight of max sidelobe / K")
        ->capture_default_str();
    cmd->add_option("--w-sidelobe-energy", o->w_sidelobe_energy,
                    "Weight of the integrated sidelobe level")
        ->capture_default_str();
    cmd->add_option("--w-min-spectrum", o->w_min_spectrum, "Weight of -min|P^(k)|/sqrt(K), k != 0")
        ->capture_default_str();
    cmd->add_option("--prior-scenes", o->prior_scenes,
                    "Natural scenes averaged for the prior power spectrum")
        ->capture_default_str();
    cmd->add_option("--keep-out", o->keep_out, "Cells no pinhole may use: none | border")
        ->capture_default_str();
    cmd->add_option("--rerank-scenes", o->rerank_scenes,
                    "Held-out scenes for the final re-ranking (not natural: the prior's family)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_flag("!--no-rerank-tv", o->rerank_tv, "Skip the TV reconstructions when re-ranking");
    cmd->add_flag("--no-rerank", o->no_rerank, "Skip the simulated re-ranking stage");
    cmd->add_option("-o,--output", o->output, "Output folder (created)")->required();
    cmd->add_flag("--json", o->json, "Print the ranking as JSON on stdout");
    cmd->add_option("--config", o->config,
                    "Settings of an earlier run (its search.config.json, or a hand-written "
                    "subset of its keys); options given here override them")
        ->check(CLI::ExistingFile);
    cmd->footer(
        "Writes rank-1.mask.json ... (provenance: seed, strategy, scores), run-log.csv, summary.md "
        "and search.config.json, all or nothing. Ctrl-C stops and writes the best so far.\n"
        "Example: pinmask search --preset paper --grid 16 --holes 20 --time 20s --seed 1 --top 5 "
        "-o runs/a/\n"
        "Repeat a run (byte-identical masks with --evals) or vary it: pinmask search --config "
        "runs/a/search.config.json --seed 2 -o runs/b/");
    cmd->callback([o, cmd] {
        if (!o->config.empty()) apply_config(io::read_search_config(o->config), *cmd, *o);
        run(*o);
    });
});

}  // namespace
}  // namespace pinmask::cli
