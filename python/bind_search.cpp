// Mask search (optimize/search.hpp, optimize/mask_objective.hpp). search() composes the steps
// of `pinmask search` (cli/cmd_search.cpp) up to its ranked candidates: template mask, kernel,
// analytic model (cli::analytic_wiener_model, the one search and compare share), objective,
// random-sparse sampling, run_search. Not here yet: keep-out cells and the simulated re-ranking
// (they live in cmd_search.cpp until the search pipeline moves into optimize/, issue 11); the
// result equals `pinmask search --no-rerank --keep-out none` for the same settings.
#include <atomic>
#include <memory>

#include "cli/analytic_setup.hpp"
#include "cli/psf_options.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "design/optics.hpp"
#include "design/psf.hpp"
#include "design/random_sparse.hpp"
#include "optimize/mask_objective.hpp"
#include "optimize/search.hpp"
#include "python/common.hpp"

namespace pinmask::python {

namespace {

constexpr const char* kGenerator = "pinmask search 0.1.0";

py::dict log_row(const SearchLogRow& row, double fraction) {
    py::dict d;
    d["seconds"] = row.seconds;
    d["evaluations"] = row.evaluations;
    d["best_objective"] = row.best_objective;
    d["budget_fraction"] = fraction;
    return d;
}

}  // namespace

void bind_search(py::module_& m) {
    m.def(
        "search",
        [](const std::optional<Camera>& camera, int grid, int holes, int tiles, double spacing,
           const std::string& kernel, const std::string& kernel_path,
           std::optional<int> pixels_per_cell, const std::string& strategy, const std::string& time,
           std::int64_t evals, int threads, std::uint64_t seed, int top, double snr_db,
           const std::string& filter, double w_analytic, double w_max_sidelobe,
           double w_sidelobe_energy, double w_min_spectrum, int prior_scenes,
           const py::object& progress, double log_interval_s) {
            Mask tmpl;
            tmpl.camera = camera.value_or(paper_camera());
            validate(tmpl.camera);
            parse_kernel_model(kernel, "--kernel");
            cli::PsfOptions po;
            po.kernel = kernel;
            po.kernel_path = kernel_path;
            po.pixels_per_cell = pixels_per_cell;
            tmpl.psf = cli::resolve_psf_spec(po, tmpl.camera);
            tmpl.pattern.n = grid;
            tmpl.pattern.tiles_rows = tmpl.pattern.tiles_cols = tiles;
            tmpl.pattern.min_spacing_cells = spacing;
            validate(tmpl.pattern);
            if (holes < 1) throw invalid_field("--holes", std::to_string(holes), "must be >= 1");
            if (strategy != "random" && strategy != "anneal")
                throw invalid_field("--strategy", strategy, "must be random or anneal");
            SearchOptions so;
            so.strategy = strategy == "random" ? SearchStrategy::kRandom : SearchStrategy::kAnneal;
            so.threads = threads;
            so.time_budget_s = evals > 0 ? 0.0 : parse_duration_s(time, "--time");
            so.max_evaluations = evals;
            so.seed = seed;
            so.top = top;
            so.log_interval_s = log_interval_s;
            so.validate();
            const WienerFilterSpec filter_spec = cli::parse_wiener_filter(filter);
            ObjectiveWeights weights{w_analytic, w_max_sidelobe, w_sidelobe_energy, w_min_spectrum};
            weights.validate();

            RandomSparseOptions ro;
            ro.n = grid;
            ro.holes = holes;
            ro.min_spacing_cells = spacing;
            ro.tiles_rows = ro.tiles_cols = tiles;
            std::atomic<bool> cancel{false};
            std::exception_ptr py_error;
            Poll poll = Poll::kContinue;
            SearchSummary summary;
            {
                py::gil_scoped_release release;
                const int n = grid, ppc = tmpl.psf.pixels_per_cell;
                check_psf_memory(n, ppc, 4, 2);
                const Kernel k = mask_kernel(tmpl);
                std::shared_ptr<const AnalyticWienerModel> model;
                if (weights.analytic_wiener > 0.0) {
                    model = std::make_shared<AnalyticWienerModel>(
                        cli::analytic_wiener_model(k, n, ppc, snr_db, prior_scenes));
                }
                const MaskObjective objective(weights, model, filter_spec);
                {
                    std::mt19937_64 probe(seed);  // infeasible requests fail before threads start
                    random_sparse_pattern(ro, probe);
                }
                summary = run_search(
                    objective, so,
                    [&](std::mt19937_64& rng) { return random_sparse_pattern(ro, rng); }, &cancel,
                    [&](const SearchLogRow& row, double fraction) {
                        if (cancel.load()) return;
                        poll = poll_python(
                            progress, [&] { return py::object(log_row(row, fraction)); },
                            &py_error);
                        if (poll != Poll::kContinue) cancel.store(true);
                    });
            }
            if (py_error) std::rethrow_exception(py_error);
            // Ctrl-C that cut nothing short (the search had finished) is not swallowed.
            if (poll == Poll::kKeyboardInterrupt && summary.stop_reason != "interrupted")
                raise_keyboard_interrupt();
            if (summary.ranked.empty())
                throw RuntimeFailure("search stopped before any evaluation");
            py::list candidates;
            for (const Candidate& c : summary.ranked) {
                Mask r = tmpl;
                r.pattern = c.pattern;
                r.pattern.pinholes = sorted_pinholes(c.pattern);
                r.provenance.seed = seed;
                r.provenance.generator = kGenerator;
                r.provenance.family = "search:" + strategy;
                r.provenance.scores = c.terms;
                py::dict d;
                d["mask"] = r;
                d["objective"] = c.objective;
                d["terms"] = c.terms;
                candidates.append(d);
            }
            py::list log;
            for (const auto& row : summary.log) log.append(log_row(row, 0.0));
            py::dict out;
            out["candidates"] = candidates;
            out["evaluations"] = summary.evaluations;
            out["evaluations_per_chain"] = summary.evaluations_per_chain;
            out["seconds"] = summary.seconds;
            out["stop_reason"] = summary.stop_reason;
            out["log"] = log;
            return out;
        },
        py::arg("camera") = py::none(), py::arg("grid") = 16, py::arg("holes") = 20,
        py::arg("tiles") = 2, py::arg("spacing") = 2.0, py::arg("kernel") = "auto",
        py::arg("kernel_path") = "", py::arg("pixels_per_cell") = py::none(),
        py::arg("strategy") = "anneal", py::arg("time") = "20s", py::arg("evals") = 0,
        py::arg("threads") = 1, py::arg("seed") = 1, py::arg("top") = 5, py::arg("snr_db") = 30.0,
        py::arg("filter") = "optimal", py::arg("w_analytic") = 1.0, py::arg("w_max_sidelobe") = 0.0,
        py::arg("w_sidelobe_energy") = 0.0, py::arg("w_min_spectrum") = 0.0,
        py::arg("prior_scenes") = cli::kDefaultPriorScenes, py::arg("progress") = py::none(),
        py::arg("log_interval_s") = 0.25,
        R"(Searches masks for a camera (grid n, holes K, tiles, spacing in cells), as
`pinmask search --no-rerank --keep-out none`: strategy random | anneal, a time budget (time,
'20s', '2min') or evals per chain (> 0: deterministic for the same seed and threads), threads
independent chains, top candidates; objective: the weighted sum of analytic_wiener (-expected
Wiener PSNR in dB at snr_db, filter 'optimal' or 'nsr:VALUE', prior of prior_scenes natural
textures), max_sidelobe, sidelobe_energy, min_spectrum.
progress(row) is called about every log_interval_s seconds with {seconds, evaluations,
best_objective, budget_fraction}; returning False stops the search. Ctrl-C (KeyboardInterrupt)
stops it too: the best candidates so far are returned, stop_reason 'interrupted'.
Returns {candidates: [{mask, objective, terms}] best first, evaluations,
evaluations_per_chain, seconds, stop_reason, log}. Keep-out cells and the simulated
re-ranking are command-line only for now.)");
}

}  // namespace pinmask::python
