// Mask search: search() is `pinmask search` up to its ranked masks, one call of the library
// pipeline optimize/search/search_pipeline (run_search_pipeline: sampling with keep-out cells, the
// search on the analytic objective, the spectral-zero rule, the simulated re-ranking, top-k).
#include <atomic>
#include <filesystem>
#include <memory>
#include <tuple>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "design/optics/optics.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_settings.hpp"
#include "io/checkpoint.hpp"
#include "io/search_config.hpp"
#include "io/search_json.hpp"
#include "io/search_run_config.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/level_args.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

py::dict log_row(const SearchLogRow& row) {
    py::dict d;
    d["seconds"] = row.seconds;
    d["evaluations"] = row.evaluations;
    d["best_objective"] = row.best_objective;
    return d;
}

// p.islands from checkpoint / checkpoint_every / resume (the checks of the command's
// cli/search_cluster, in Python's words).
void set_checkpoints(SearchPipelineOptions& p, const io::SearchRunTexts& texts,
                     const std::optional<std::string>& checkpoint, std::int64_t every,
                     const std::optional<std::string>& resume) {
    namespace fs = std::filesystem;
    const nlohmann::ordered_json config =
        io::checkpoint_config(io::resolved_search_config(p, texts, "", 1), 1, 0, every);
    p.islands.checkpoint_every = every;
    if (every < 0)
        throw invalid_field(field_ref("checkpoint_every"), std::to_string(every), "must be >= 0");
    if (every > 0 && !checkpoint)
        throw InvalidInput(field_ref("checkpoint_every") + ": needs " + field_ref("checkpoint") +
                           " FILE");
    if (checkpoint) {
        if (every <= 0)
            throw InvalidInput(field_ref("checkpoint") + ": needs " +
                               field_ref("checkpoint_every") + " E (evaluations per chain)");
        const fs::path path = *checkpoint;
        if (checkpoint->empty() || fs::is_directory(path))
            throw invalid_field(field_ref("checkpoint"), *checkpoint,
                                "is a directory, not a file name");
        const fs::path parent = path.has_parent_path() ? path.parent_path() : ".";
        if (!fs::is_directory(parent))
            throw invalid_field(field_ref("checkpoint"), *checkpoint, "its folder does not exist");
        if (p.search.max_evaluations == 0)
            throw InvalidInput(field_ref("checkpoint") + ": needs an evaluation budget (" +
                               field_ref("max_evaluations") +
                               "); a time-budget run does not end at a reproducible point");
        p.islands.checkpoint = io::checkpoint_writer(path, config);
    }
    p.islands.validate();
    if (!resume) return;
    const io::SearchCheckpointFile c =
        io::checkpoint_to_resume(*resume, config, checkpoint.value_or(""));
    p.islands.resume_segment = c.segment;
    p.islands.resume = c.chains;
}

}  // namespace

void bind_search(py::module_& m) {
    m.def(
        "search",
        [](const std::optional<Camera>& camera, int grid, const py::object& holes, int tiles,
           double spacing, const std::string& kernel, const std::string& kernel_path,
           std::optional<int> pixels_per_cell, const std::string& strategy, const std::string& time,
           std::int64_t evals, int threads, std::uint64_t seed, int top, const py::object& snr_db,
           const std::string& filter, double w_analytic, double w_max_sidelobe,
           double w_sidelobe_energy, double w_min_spectrum, int prior_scenes,
           const std::string& keep_out, const std::vector<std::string>& rerank_scenes,
           bool rerank_tv, const std::string& rank_by, bool allow_spectral_zeros,
           const py::object& progress, const py::object& photons, std::optional<double> read_noise,
           std::optional<double> dark_current, std::optional<double> full_well,
           std::optional<int> bits, std::optional<double> optical_density, const py::object& prior,
           const std::optional<std::string>& robust, const std::string& objective,
           const std::optional<std::string>& checkpoint, std::int64_t checkpoint_every,
           const std::optional<std::string>& resume, double depth_weight,
           std::optional<double> depth_from, std::optional<double> depth_to) {
            SearchPipelineOptions p;
            p.tmpl.camera = camera.value_or(paper_camera());
            validate(p.tmpl.camera);
            parse_kernel_model(kernel, field_ref("kernel"));
            PsfSettings po;
            po.kernel = kernel;
            po.kernel_path = kernel_path;
            po.pixels_per_cell = pixels_per_cell;
            p.tmpl.psf = resolve_psf_spec(po, p.tmpl.camera);
            p.tmpl.pattern.n = grid;
            p.tmpl.pattern.tiles_rows = p.tmpl.pattern.tiles_cols = tiles;
            p.tmpl.pattern.min_spacing_cells = spacing;
            // holes: K, or "A..B" as --holes (a pinhole-count range: the best mask per K).
            if (py::isinstance<py::str>(holes)) {
                std::tie(p.holes, p.max_holes) = parse_holes_range(holes.cast<std::string>());
            } else if (py::isinstance<py::int_>(holes) && !py::isinstance<py::bool_>(holes)) {
                p.holes = holes.cast<int>();
            } else {
                throw invalid_field(field_ref("holes"), std::string(py::repr(holes)),
                                    "must be a pinhole count K or a range 'A..B'");
            }
            if (strategy != "random" && strategy != "anneal")
                throw invalid_field(field_ref("strategy"), strategy, "must be random or anneal");
            if (evals < 0)
                throw invalid_field(field_ref("evals"), std::to_string(evals),
                                    "must be >= 1 evaluations per chain (0: search for time)");
            SearchOptions& so = p.search;
            so.strategy = strategy == "random" ? SearchStrategy::kRandom : SearchStrategy::kAnneal;
            so.threads = threads;
            so.time_budget_s = evals > 0 ? 0.0 : parse_duration_s(time, field_ref("time"));
            so.max_evaluations = evals;
            so.seed = seed;
            so.top = top;
            if (top < 1 || top > 1000)
                throw invalid_field(field_ref("top"), std::to_string(top),
                                    "must be between 1 and 1000");
            p.keep_out = keep_out;
            const SensorSettings sensor{read_noise, dark_current, full_well, optical_density, bits};
            const std::vector<NoiseLevel> levels =
                noise_levels_arg(snr_db, photons, sensor, {30.0});
            if (levels.size() != 1) {
                throw InvalidInput(field_ref("snr_db") + "/" + field_ref("photons") +
                                   ": search optimises one noise level; give one value "
                                   "(score and compare take lists)");
            }
            p.noise = levels.front().model;
            p.prior = prior_arg(prior, prior_scenes);
            p.filter = parse_search_filter(filter, p.noise);
            p.weights = {w_analytic, w_max_sidelobe, w_sidelobe_energy, w_min_spectrum,
                         depth_weight};
            if (!(depth_weight > 0.0) && (depth_from || depth_to)) {
                throw InvalidInput(field_ref("depth_from_m") + "/" + field_ref("depth_to_m") +
                                   ": give " + field_ref("weights.depth") +
                                   " > 0 (the range is the depth term's)");
            }
            p.depth_range.from_m = depth_from.value_or(0.0);
            p.depth_range.to_m = depth_to.value_or(0.0);
            p.allow_spectral_zeros = allow_spectral_zeros;
            for (const auto& name : rerank_scenes) p.rerank_scenes.push_back(scene_from_name(name));
            p.rerank_tv = rerank_tv && !rerank_scenes.empty();
            p.rank_by = parse_rank_by(rank_by);
            p.generator = io::kSearchGenerator;
            // robust / objective: the same parsers and the same pipeline as the CLI.
            if (robust) p.robust = parse_fabrication_errors(*robust);
            p.objective = parse_objective_kind(objective);
            p.validate();
            // Checkpoints, as `search --checkpoint F --checkpoint-every E` / `--resume F`: the
            // file records the run's resolved configuration (io/search_run_config, the command's
            // own), so a checkpoint of either face resumes in the other with the same settings.
            io::SearchRunTexts texts;
            texts.strategy = strategy;
            texts.time = time;
            texts.filter = filter;
            texts.keep_out = keep_out;
            texts.rank_by = rank_by;
            texts.objective = objective;
            texts.robust = robust.value_or("");
            texts.seed = seed;
            texts.top = top;
            texts.w_analytic = w_analytic;
            texts.w_max_sidelobe = w_max_sidelobe;
            texts.w_sidelobe_energy = w_sidelobe_energy;
            texts.w_min_spectrum = w_min_spectrum;
            texts.w_depth = depth_weight;
            texts.rerank_scenes = rerank_scenes;
            set_checkpoints(p, texts, checkpoint, checkpoint_every, resume);

            std::atomic<bool> cancel{false};
            std::exception_ptr py_error;
            Poll poll = Poll::kContinue;
            SearchPipelineSummary summary;
            {
                py::gil_scoped_release release;
                check_psf_memory(grid, p.tmpl.psf.pixels_per_cell, 4, 2);
                summary = run_search_pipeline(
                    p, &cancel,
                    [&](const std::string& phase, double fraction, const std::string& text) {
                        if (cancel.load()) return;
                        poll = poll_python(
                            progress,
                            [&] {
                                py::dict d;
                                d["phase"] = phase;
                                d["fraction"] = fraction;
                                d["text"] = text;
                                return py::object(d);
                            },
                            &py_error);
                        if (poll != Poll::kContinue) cancel.store(true);
                    });
            }
            if (py_error) std::rethrow_exception(py_error);
            // Ctrl-C is Python's KeyboardInterrupt, as for any call; the search stopped at it.
            // (A progress callback returning False stops it and returns the best so far.)
            if (poll == Poll::kKeyboardInterrupt) raise_keyboard_interrupt();
            // What `search --json` prints (io/search_json; nothing written: output and the
            // ranked rows' paths None), with what the command writes as files as values: the
            // ranked masks (rank-N.mask.json) and the search's log (run-log.csv).
            py::dict out(json_value(io::search_json(summary, "", {})));
            py::list masks;
            for (const RankedMask& c : summary.ranked) masks.append(c.mask);
            out["masks"] = masks;
            py::list log;
            for (const auto& row : summary.search.log) log.append(log_row(row));
            out["log"] = log;
            return as_result(out);
        },
        py::arg("camera") = py::none(), py::arg("grid") = 16, py::arg("holes") = 20,
        py::arg("tiles") = 2, py::arg("spacing") = 2.0, py::arg("kernel") = "auto",
        py::arg("kernel_path") = "", py::arg("pixels_per_cell") = py::none(),
        py::arg("strategy") = "anneal", py::arg("time") = "20s", py::arg("evals") = 0,
        py::arg("threads") = 1, py::arg("seed") = 1, py::arg("top") = 5,
        py::arg("snr_db") = py::none(), py::arg("filter") = "auto", py::arg("w_analytic") = 1.0,
        py::arg("w_max_sidelobe") = 0.0, py::arg("w_sidelobe_energy") = 0.0,
        py::arg("w_min_spectrum") = 0.0, py::arg("prior_scenes") = kDefaultPriorScenes,
        py::arg("keep_out") = "none",
        py::arg("rerank_scenes") = std::vector<std::string>{"letter-R", "usaf", "siemens-star"},
        py::arg("rerank_tv") = true, py::arg("rank_by") = "wiener",
        py::arg("allow_spectral_zeros") = false, py::arg("progress") = py::none(),
        py::arg("photons") = py::none(), py::arg("read_noise") = py::none(),
        py::arg("dark_current") = py::none(), py::arg("full_well") = py::none(),
        py::arg("bits") = py::none(), py::arg("optical_density") = py::none(),
        py::arg("prior") = "natural", py::arg("robust") = py::none(),
        py::arg("objective") = "nominal", py::arg("checkpoint") = py::none(),
        py::arg("checkpoint_every") = 0, py::arg("resume") = py::none(),
        py::arg("depth_weight") = 0.0, py::arg("depth_from") = py::none(),
        py::arg("depth_to") = py::none(),
        R"(Searches masks for a camera (grid n, holes K or a range 'A..B', tiles, spacing in cells) as
`pinmask search` (the same pipeline, optimize/search/search_pipeline): strategy random | anneal, a
time budget (time, '20s', '2min'; it covers the re-ranking too) or evals per chain (> 0:
deterministic for the same seed and threads), threads independent chains, top candidates,
keep_out 'none' | 'border'; objective: the weighted sum of analytic_wiener (-expected Wiener PSNR
at the noise level, filter 'auto' (tuned with photons, optimal with snr_db), 'optimal', 'tuned'
or 'nsr:VALUE', prior as in metrics()),
max_sidelobe, sidelobe_energy, min_spectrum, and with depth_weight W > 0 (needs photons) the
depth term W x 20 log10(worst sigma_u / u) dB over depth_from .. depth_to metres (None, None:
the working distance / 2 .. x 2; score's depth_crb_rel with the Fisher information summed
pinhole by pinhole; terms depth_crb_rel, depth_crb_rel_db); patterns with a spectral zero are
rejected unless
allow_spectral_zeros. The top candidates are re-ranked by simulated decodes of rerank_scenes
(empty list: no re-ranking, as --no-rerank) ranked by rank_by 'wiener' | 'tv'.
progress(row) is called with {phase: 'search' | 'rerank', fraction, text}; returning False
stops the search: the best candidates so far are returned, stop_reason 'interrupted'. Ctrl-C
stops it and raises KeyboardInterrupt.
Noise: ONE level, snr_db (Gaussian, dB; None: 30) or photons (electrons per pixel per pinhole)
with read_noise, dark_current, full_well, bits, optical_density, as metrics().
robust (as --robust, e.g. 'size=44um,jitter=2um'): every candidate's terms gain
analytic_robust_mmse_psnr_db or analytic_robust_wiener_psnr_db (by the filter; expected under
those fabrication errors, nominal-PSF decoder);
objective 'robust' (needs robust) optimises it, 'nominal' (default) the design's figure.
Checkpoints (as --checkpoint / --checkpoint-every / --resume; needs evals): checkpoint=FILE
with checkpoint_every=E writes every chain's state atomically every E evaluations per chain;
resume=FILE continues from a checkpoint of the same settings (the command's file format and
configuration: one written by `pinmask search` on one process with the same settings resumes
here, and back), and the result equals the uninterrupted run's.
Returns what `pinmask search --json` prints (io/search_json) with nothing written: {output
(None), evaluations, evaluations_per_chain, stop_reason, planned_s, used_s (all), search_s,
rerank_s, reranked, psnr_columns, reordered, objective_figure (the terms key the objective
weighs), ranked: [{rank, path (None), geometry_hash, objective, reranked, every term under
score's names (analytic_mmse_psnr_db; with a fixed or tuned filter analytic_wiener_psnr_db and
analytic_wiener_nsr; max_sidelobe, ...) and simulated figure (sim_wiener_psnr_db,
sim_tv_psnr_db, sim_tv_lambda, ...), upper_bound_analytic_mmse_psnr_db (the analytic MMSE PSNR
no pattern with the candidate's K can exceed)}] best first, best_per_holes (with a range of
holes: the best row per K)}; and, what the command writes as files, masks: the ranked Mask
objects in rank order (rank-N.mask.json) and log: [{seconds, evaluations, best_objective}]
(run-log.csv).)");
}

}  // namespace pinmask::python
