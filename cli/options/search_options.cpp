#include "cli/options/search_options.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "cli/options/analytic_setup.hpp"
#include "cli/options/camera_options.hpp"
#include "cli/options/depth_range_flags.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/options/psf_options.hpp"
#include "core/errors/error.hpp"
#include "core/units/units.hpp"
#include "io/optics_json.hpp"
#include "io/search_config.hpp"
#include "io/search_run_config.hpp"

namespace pinmask::cli {

void apply_config(const io::SearchConfig& c, const CLI::App& cmd, SearchCliOptions& o) {
    auto given = [&](const char* flag) { return cmd.get_option(flag)->count() > 0; };
    auto set = [&](const char* flag, auto& field, const auto& value) {
        if (value && !given(flag)) field = *value;
    };
    o.config_ranks = c.ranks;
    set("--strategy", o.strategy, c.strategy);
    set("--time", o.time, c.time);
    // A --time on the command line replaces the file's evaluation budget (and --evals its time).
    if (!given("--time") && c.evaluations_per_chain && *c.evaluations_per_chain > 0)
        set("--evals", o.evals, c.evaluations_per_chain);
    set("--threads", o.threads, c.threads);
    set("--seed", o.seed, c.seed);
    set("--top", o.top, c.top);
    set("--grid", o.geometry.grid, c.grid);
    if (c.holes && !given("--holes")) {
        o.holes = std::to_string(*c.holes);
        if (c.max_holes && *c.max_holes > 0) o.holes += ".." + std::to_string(*c.max_holes);
    }
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
    set("--depth-weight", o.w_depth, c.w_depth);
    set("--depth-from", o.depth_from, c.depth_from);
    set("--depth-to", o.depth_to, c.depth_to);
    if (c.rerank_scenes && !given("--rerank-scenes") && !given("--no-rerank")) {
        if (c.rerank_scenes->empty())
            o.no_rerank = true;  // written for a run with --no-rerank
        else
            o.rerank_scenes = *c.rerank_scenes;
    }
    set("--no-rerank-tv", o.rerank_tv, c.rerank_tv);
    set("--allow-spectral-zeros", o.allow_spectral_zeros, c.allow_spectral_zeros);
    set("--rank-by", o.rank_by, c.rank_by);
    set("--objective", o.objective, c.objective);
    set("--robust", o.robust, c.robust);
    // The file's camera replaces the preset unless --preset is given.
    if (c.optics && !given("--preset")) o.camera.base = c.optics;
}

nlohmann::ordered_json resolved_config(const SearchCliOptions& o, const SearchPipelineOptions& p,
                                       const SearchPipelineSummary& s, int ranks) {
    io::SearchRunTexts t;
    t.strategy = o.strategy;
    t.time = o.time;
    t.filter = o.filter;
    t.keep_out = o.keep_out;
    t.rank_by = o.rank_by;
    t.objective = o.objective;
    t.robust = o.robust;
    t.seed = o.seed;
    t.top = o.top;
    t.w_analytic = o.w_analytic;
    t.w_max_sidelobe = o.w_max_sidelobe;
    t.w_sidelobe_energy = o.w_sidelobe_energy;
    t.w_min_spectrum = o.w_min_spectrum;
    t.w_depth = o.w_depth;
    if (!o.no_rerank) t.rerank_scenes = o.rerank_scenes;
    return io::resolved_search_config(p, t, s.kernel_resolved, ranks);
}

SearchPipelineOptions search_pipeline_options(const SearchCliOptions& o, const CLI::App& cmd) {
    SearchPipelineOptions p;
    const Camera camera = resolve_camera(o.camera);
    p.tmpl.camera = camera;
    p.tmpl.psf = resolve_psf_spec(o.psf, camera);
    p.tmpl.pattern.n = o.geometry.grid;
    p.tmpl.pattern.tiles_rows = p.tmpl.pattern.tiles_cols = o.geometry.tiles;
    p.tmpl.pattern.min_spacing_cells = o.geometry.spacing;
    std::tie(p.holes, p.max_holes) = parse_holes_range(o.holes);
    SearchOptions& so = p.search;
    so.strategy = o.strategy == "random" ? SearchStrategy::kRandom : SearchStrategy::kAnneal;
    if (o.threads < 0)
        throw invalid_field("--threads", std::to_string(o.threads), "must be >= 1 (0: all cores)");
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
    p.keep_out = o.keep_out;
    const std::vector<NoiseLevel> levels = noise_levels(o.noise, cmd);
    if (levels.size() != 1) {
        throw InvalidInput(
            "--snr/--photons: search optimises one noise level; give one value "
            "(score and compare take lists)");
    }
    p.noise = levels.front().model;
    p.prior = prior_spec(o.prior);
    p.filter = parse_search_filter(o.filter, p.noise);
    p.weights = {o.w_analytic, o.w_max_sidelobe, o.w_sidelobe_energy, o.w_min_spectrum, o.w_depth};
    p.depth_range =
        depth_range_of(cmd, o.depth_from, o.depth_to, o.w_depth > 0.0, "give --depth-weight > 0");
    p.allow_spectral_zeros = o.allow_spectral_zeros;
    if (!o.no_rerank)
        for (const auto& name : o.rerank_scenes) p.rerank_scenes.push_back(scene_from_name(name));
    p.rerank_tv = o.rerank_tv && !o.no_rerank;
    p.rank_by = parse_rank_by(o.rank_by);
    p.objective = parse_objective_kind(o.objective);
    if (!o.robust.empty()) p.robust = parse_fabrication_errors(o.robust);
    p.generator = kSearchGenerator;
    p.validate();
    return p;
}

}  // namespace pinmask::cli
