// `pinmask search`: find masks for a camera that decode better than random draws. Parses flags
// (and --config), calls optimize/search_pipeline, writes the outputs (cli/search_outputs).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "cli/analytic_setup.hpp"
#include "cli/camera_options.hpp"
#include "cli/command.hpp"
#include "cli/interrupt.hpp"
#include "cli/noise_options.hpp"
#include "cli/progress.hpp"
#include "cli/psf_options.hpp"
#include "cli/search_outputs.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "io/optics_json.hpp"
#include "io/search_config.hpp"
#include "optimize/search_pipeline.hpp"

namespace pinmask::cli {
namespace {

constexpr const char* kGenerator = "pinmask search 0.1.0";

struct Options {
    CameraOptions camera;
    GeometryOptions geometry;
    PsfOptions psf;
    std::string strategy = "anneal", time = "20s", filter = "optimal", keep_out = "none";
    std::optional<std::int64_t> evals;
    int threads = 0, top = 5;
    std::uint64_t seed = 1;
    NoiseFlags noise;
    PriorFlags prior;
    double w_analytic = 1.0, w_max_sidelobe = 0.0, w_sidelobe_energy = 0.0, w_min_spectrum = 0.0;
    std::vector<std::string> rerank_scenes{"letter-R", "usaf", "siemens-star"};
    bool rerank_tv = true, no_rerank = false, allow_spectral_zeros = false, json = false,
         quiet = false;
    std::string rank_by = "wiener", output, config;
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
    if (!given("--time") && c.evaluations_per_chain && *c.evaluations_per_chain > 0)
        set("--evals", o.evals, c.evaluations_per_chain);
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
    if (c.snr_db && !given("--snr") && !given("--photons")) o.noise.snr = std::to_string(*c.snr_db);
    if (c.photons && !given("--snr") && !given("--photons")) {
        o.noise.photons = std::to_string(*c.photons);
        set("--read-noise", o.noise.sensor.read_noise, c.read_noise);
        set("--dark-current", o.noise.sensor.dark_current, c.dark_current);
        if (c.full_well && std::isfinite(*c.full_well))
            set("--full-well", o.noise.sensor.full_well, c.full_well);
        if (c.bits && *c.bits > 0) set("--bits", o.noise.sensor.bits, c.bits);
        if (c.optical_density && std::isfinite(*c.optical_density))
            set("--optical-density", o.noise.sensor.optical_density, c.optical_density);
    }
    set("--filter", o.filter, c.filter);
    set("--prior-scenes", o.prior.count, c.prior_scenes);
    if (c.prior_family && !given("--prior")) {
        o.prior.prior = *c.prior_family;
        if (*c.prior_family == "files") {
            o.prior.prior.clear();
            for (const auto& f : c.prior_files.value_or(std::vector<std::string>{}))
                o.prior.prior += (o.prior.prior.empty() ? "" : ",") + f;
        }
    }
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
    set("--allow-spectral-zeros", o.allow_spectral_zeros, c.allow_spectral_zeros);
    set("--rank-by", o.rank_by, c.rank_by);
    // The file's camera replaces the preset unless --preset is given.
    if (c.optics && !given("--preset")) o.camera.base = c.optics;
}

SearchPipelineOptions make_options(const Options& o, const CLI::App& cmd) {
    SearchPipelineOptions p;
    const Camera camera = resolve_camera(o.camera);
    p.tmpl.camera = camera;
    p.tmpl.psf = resolve_psf_spec(o.psf, camera);
    p.tmpl.pattern.n = o.geometry.grid;
    p.tmpl.pattern.tiles_rows = p.tmpl.pattern.tiles_cols = o.geometry.tiles;
    p.tmpl.pattern.min_spacing_cells = o.geometry.spacing;
    p.holes = o.geometry.holes;
    SearchOptions& so = p.search;
    so.strategy = o.strategy == "random" ? SearchStrategy::kRandom : SearchStrategy::kAnneal;
    so.threads = o.threads > 0 ? o.threads
                               : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    if (o.evals && *o.evals < 1) {
        throw invalid_field("--evals", std::to_string(*o.evals),
                            "must be >= 1 evaluations per chain (leave it out to search for "
                            "--time instead)");
    }
    so.time_budget_s = o.evals ? 0.0 : parse_duration_s(o.time, "--time");
    so.max_evaluations = o.evals.value_or(0);
    so.seed = o.seed;
    so.top = o.top;
    if (o.top < 1 || o.top > 1000)
        throw invalid_field("--top", std::to_string(o.top), "must be between 1 and 1000");
    p.keep_out = o.keep_out;
    const std::vector<NoiseLevel> levels = noise_levels(o.noise, cmd);
    if (levels.size() != 1) {
        throw InvalidInput(
            "--snr/--photons: search optimises one noise level; give one value "
            "(score and compare take lists)");
    }
    p.noise = levels.front().model;
    p.prior = prior_spec(o.prior);
    p.filter = parse_wiener_filter(o.filter);
    p.weights = {o.w_analytic, o.w_max_sidelobe, o.w_sidelobe_energy, o.w_min_spectrum};
    p.allow_spectral_zeros = o.allow_spectral_zeros;
    if (!o.no_rerank)
        for (const auto& name : o.rerank_scenes) p.rerank_scenes.push_back(scene_from_name(name));
    p.rerank_tv = o.rerank_tv && !o.no_rerank;
    p.rank_by = parse_rank_by(o.rank_by);
    p.generator = kGenerator;
    p.validate();
    if (o.output.empty()) throw InvalidInput("-o/--output: an output folder is required");
    return p;
}

nlohmann::ordered_json noise_config(const NoiseModel& m) {
    if (m.kind != NoiseKind::kPhoton) return {{"model", "gaussian"}, {"snr_db", m.snr_db}};
    const nlohmann::ordered_json j = noise_json(m);  // null for an infinite full well or OD
    return {{"model", "photon"},
            {"photons_per_pinhole", m.photons_per_pinhole},
            {"read_noise_e", m.read_noise_e},
            {"dark_current_e", m.dark_current_e},
            {"full_well_e", j["full_well_e"]},
            {"adc_bits", m.adc_bits},
            {"film_optical_density", j["film_optical_density"]}};
}

nlohmann::ordered_json resolved_config(const Options& o, const SearchPipelineOptions& p,
                                       const SearchPipelineSummary& s) {
    nlohmann::ordered_json prior{{"family", prior_kind_name(p.prior.kind)},
                                 {"scenes", p.prior.count}};
    if (p.prior.kind == PriorKind::kFiles) {
        prior["files"] = nlohmann::ordered_json::array();
        for (const auto& f : p.prior.files) prior["files"].push_back(f.string());
    }
    return {{"format", io::kSearchConfigFormat},
            {"version", io::kSearchConfigVersion},
            {"generator", kGenerator},
            {"strategy", o.strategy},
            {"time", o.time},
            {"evaluations_per_chain", p.search.max_evaluations},
            {"threads", p.search.threads},
            {"seed", o.seed},
            {"top", o.top},
            {"grid", p.tmpl.pattern.n},
            {"holes", p.holes},
            {"tiles", p.tmpl.pattern.tiles_rows},
            {"min_spacing_cells", p.tmpl.pattern.min_spacing_cells},
            {"keep_out", o.keep_out},
            {"pixels_per_cell", p.tmpl.psf.pixels_per_cell},
            {"kernel_requested", p.tmpl.psf.kernel.model},
            {"kernel_resolved", s.kernel_resolved},
            {"kernel_path", p.tmpl.psf.kernel.measured_path},
            {"noise", noise_config(p.noise)},
            {"filter", o.filter},
            {"prior", prior},
            {"weights",
             {{"analytic_wiener", o.w_analytic},
              {"max_sidelobe", o.w_max_sidelobe},
              {"sidelobe_energy", o.w_sidelobe_energy},
              {"min_spectrum", o.w_min_spectrum}}},
            {"rerank_scenes", o.no_rerank ? std::vector<std::string>{} : o.rerank_scenes},
            {"rerank_tv", p.rerank_tv},
            {"allow_spectral_zeros", p.allow_spectral_zeros},
            {"rank_by", o.rank_by},
            {"optics", io::optics_to_json<nlohmann::ordered_json>(p.tmpl.camera)}};
}

void run(const Options& o, const CLI::App& cmd) {
    const SearchPipelineOptions p = make_options(o, cmd);
    ProgressLine bar;
    const auto& interrupted = install_interrupt_flag();
    const SearchPipelineSummary s = run_search_pipeline(
        p, &interrupted, [&](const std::string& phase, double fraction, const std::string& text) {
            if (!o.quiet) bar.update(fraction, phase + ": " + text);
        });
    bar.finish();
    if (s.termination == SearchTermination::kInterrupted) {
        std::cerr << "pinmask search: interrupted; writing the best " << s.ranked.size()
                  << " candidate(s) found so far\n";
    }
    const auto paths = write_search_outputs(o.output, s, resolved_config(o, p, s));
    if (!o.json) {
        std::cout << search_summary_markdown(s) << "wrote " << paths.size()
                  << " masks, run-log.csv, timing.csv, summary.md and search.config.json to "
                  << o.output << "\n";
        return;
    }
    nlohmann::ordered_json j{{"output", o.output},
                             {"evaluations", s.search.evaluations},
                             {"evaluations_per_chain", s.search.evaluations_per_chain},
                             {"stop_reason", search_termination_name(s.termination)},
                             {"planned_s", s.planned_s},
                             {"used_s", s.used_s},
                             {"search_s", s.search_s},
                             {"rerank_s", s.rerank_s},
                             {"reranked", s.reranked}};
    for (std::size_t i = 0; i < s.ranked.size(); ++i) {
        nlohmann::ordered_json r{{"rank", i + 1},
                                 {"path", paths[i].string()},
                                 {"geometry_hash", geometry_hash(s.ranked[i].mask)},
                                 {"objective", s.ranked[i].objective},
                                 {"reranked", s.ranked[i].reranked}};
        for (const auto& [k, v] : s.ranked[i].mask.provenance.scores) r[k] = v;
        j["ranked"].push_back(r);
    }
    std::cout << j.dump(2) << "\n";
}

const Registration kSearch(50, "search", [](CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand(
        "search",
        "Search random sparse cyclic patterns under the spacing rule for the mask that decodes "
        "best. The objective is the analytic expected Wiener PSNR (closed form from the OTF, the "
        "scene prior and the noise model: Gaussian --snr or the photon model --photons) plus "
        "optional sidelobe and spectrum terms; patterns with a spectral zero are rejected; the "
        "top candidates are re-ranked by simulated Wiener or TV reconstruction of held-out "
        "scenes, all inside --time.");
    add_camera_options(*cmd, o->camera);
    add_geometry_options(*cmd, o->geometry);
    add_psf_options(*cmd, o->psf);
    cmd->add_option("--strategy", o->strategy,
                    "random: sample valid patterns, keep the best (the paper's approach, the "
                    "baseline); anneal: simulated annealing moving one pinhole at a time")
        ->check(CLI::IsMember({"random", "anneal"}))
        ->capture_default_str();
    cmd->add_option("--time", o->time,
                    "Wall-clock budget of the whole run, re-ranking included (e.g. 20s, 2min)")
        ->capture_default_str();
    cmd->add_option("--evals", o->evals,
                    "Evaluation budget per chain (>= 1) instead of --time: same seed and thread "
                    "count give identical masks, run-log.csv and summary.md");
    cmd->add_option("--threads", o->threads, "Independent chains (default: all cores)");
    cmd->add_option("--seed", o->seed, "Seed of every chain's generator")->capture_default_str();
    cmd->add_option("--top", o->top, "Candidates to keep and write (1..1000)")
        ->capture_default_str();
    add_noise_flags(*cmd, o->noise, "30");
    add_prior_flags(*cmd, o->prior);
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
    cmd->add_option("--keep-out", o->keep_out, "Cells no pinhole may use: none | border")
        ->capture_default_str();
    cmd->add_flag("--allow-spectral-zeros", o->allow_spectral_zeros,
                  "Keep patterns whose |P^(k)| < 1e-3 sqrt(K) at a frequency the kernel passes "
                  "(flagged in the summary); by default they are rejected");
    cmd->add_option("--rerank-scenes", o->rerank_scenes,
                    "Held-out scenes for the final re-ranking (not natural with the natural prior)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--rank-by", o->rank_by,
                    "Decoder whose simulated PSNR orders the re-ranked candidates: wiener, or tv "
                    "(TV-L2 with lambda tuned per mask on the re-ranking scenes; slower)")
        ->capture_default_str();
    cmd->add_flag("!--no-rerank-tv", o->rerank_tv, "Skip the TV reconstructions when re-ranking");
    cmd->add_flag("--no-rerank", o->no_rerank, "Skip the simulated re-ranking stage");
    cmd->add_option("-o,--output", o->output, "Output folder (created)")->required();
    cmd->add_flag("--json", o->json, "Print the ranking as JSON on stdout");
    cmd->add_flag("--quiet", o->quiet, "No progress line on stderr");
    cmd->add_option("--config", o->config,
                    "Settings of an earlier run (its search.config.json, or a hand-written "
                    "subset of its keys); options given here override them")
        ->check(CLI::ExistingFile);
    cmd->footer(
        "Writes rank-1.mask.json ... (provenance: seed, strategy, scores), run-log.csv (best "
        "objective at fixed evaluation counts), timing.csv (wall clock), summary.md and "
        "search.config.json, all or nothing. With --evals, masks, run-log.csv, summary.md and "
        "search.config.json are byte-identical run to run. Ctrl-C (or SIGTERM) stops and writes "
        "the best so far; a second signal only hurries it.\n"
        "Example: pinmask search --preset paper --grid 16 --holes 20 --time 20s --seed 1 --top 5 "
        "-o runs/a/\n"
        "Dim light: pinmask search --photons 3 --read-noise 3 --holes 30 --time 30s -o runs/dim/\n"
        "Repeat a run (byte-identical masks with --evals) or vary it: pinmask search --config "
        "runs/a/search.config.json --seed 2 -o runs/b/");
    cmd->callback([o, cmd] {
        if (!o->config.empty()) apply_config(io::read_search_config(o->config), *cmd, *o);
        run(*o, *cmd);
    });
});

}  // namespace
}  // namespace pinmask::cli
