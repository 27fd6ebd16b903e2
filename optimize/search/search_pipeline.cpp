#include "optimize/search/search_pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "design/pattern/packing_bound.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/kernel_model.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"
#include "optimize/search/depth_term.hpp"
#include "optimize/search/island_search.hpp"
#include "optimize/search/objective_bound.hpp"
#include "optimize/search/rerank_order.hpp"

namespace pinmask {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// At most this fraction of a time budget is held back for re-ranking.
constexpr double kMaxRerankShare = 0.5;
// Margin on the timed re-ranking of one pattern: on a loaded machine one decode scatters by
// tens of per cent and later candidates can cost more than the probe.
constexpr double kRerankMargin = 2.0;
// Decoder runs per scene of a tuned weight: golden section over 8 decades to 0.01 decade
// (optimize/metrics/nsr_tuning: ~15 steps) plus the end points and the final decode.
constexpr double kTunedDecodesPerScene = 18.0;

// The mask objective, with patterns that have a spectral zero in the kernel passband rejected
// (objective +inf: annealing never accepts them, the top list never keeps them).
class PipelineObjective : public SearchObjective {
  public:
    PipelineObjective(const SearchObjective& inner, std::vector<std::uint8_t> passed, bool reject)
        : inner_(inner), passed_(std::move(passed)), reject_(reject) {}
    double evaluate(const PatternState& s) const override {
        if (reject_ && find_spectral_zero(s.spectrum(), passed_).found) return INFINITY;
        return inner_.evaluate(s);
    }
    std::map<std::string, double> terms(const PatternState& s) const override {
        return inner_.terms(s);
    }

  private:
    const SearchObjective& inner_;
    std::vector<std::uint8_t> passed_;
    bool reject_;
};

// A random valid pattern avoiding keep-out cells: the random family, then each pinhole that sits
// in a keep-out cell moved to a random legal cell outside it.
Pattern sample_pattern(const RandomSparseOptions& ro, const std::vector<Cell>& keep_out,
                       const std::string& keep_out_name, std::mt19937_64& rng) {
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
            throw invalid_field(field_ref("keep_out"), keep_out_name,
                                "no legal cell left outside the keep-out area for " +
                                    std::to_string(ro.holes) + " pinholes");
        }
    }
    return s.pattern();
}

struct Reranker {
    std::vector<NamedScene> scenes;
    NoiseModel noise;
    SimulatedMetricsOptions sim;
    bool tv = false;
    RankBy rank_by = RankBy::kWiener;

    void apply(RankedMask& r) const {
        const Plane psf = mask_psf(r.mask);
        const int k = static_cast<int>(r.mask.pattern.pinholes.size());
        const int cells = r.mask.pattern.n * r.mask.pattern.n;
        const SimulatedQuality w =
            simulated_quality(psf, scenes, noise, k, cells, SimulatedDecoder::kWiener, sim);
        r.sim_wiener_psnr_db = w.mean_psnr_db;
        r.sim_scene_psnr_db.clear();
        for (const SceneQuality& q : w.scenes) r.sim_scene_psnr_db.push_back(q.psnr_db);
        r.mask.provenance.scores["sim_wiener_psnr_db"] = r.sim_wiener_psnr_db;
        if (tv) {
            const SimulatedQuality q =
                simulated_quality(psf, scenes, noise, k, cells, SimulatedDecoder::kTv, sim);
            r.sim_tv_psnr_db = q.mean_psnr_db;
            r.tv_lambda = q.weight;
            if (rank_by == RankBy::kTv) {
                r.sim_scene_psnr_db.clear();
                for (const SceneQuality& sq : q.scenes) r.sim_scene_psnr_db.push_back(sq.psnr_db);
            }
            r.mask.provenance.scores["sim_tv_psnr_db"] = r.sim_tv_psnr_db;
            r.mask.provenance.scores["sim_tv_lambda"] = r.tv_lambda;
        }
        r.reranked = true;
    }
};

}  // namespace

const std::vector<std::pair<RankBy, std::string>>& rank_by_names() {
    static const std::vector<std::pair<RankBy, std::string>> kNames{{RankBy::kWiener, "wiener"},
                                                                    {RankBy::kTv, "tv"}};
    return kNames;
}

std::string rank_by_name(RankBy r) {
    for (const auto& [k, name] : rank_by_names())
        if (k == r) return name;
    return "unknown";
}

RankBy parse_rank_by(const std::string& text) {
    for (const auto& [k, name] : rank_by_names())
        if (name == text) return k;
    throw invalid_field(field_ref("rank_by"), text, "must be wiener or tv");
}

ObjectiveKind parse_objective_kind(const std::string& text) {
    if (text == "nominal") return ObjectiveKind::kNominal;
    if (text == "robust") return ObjectiveKind::kRobust;
    if (text == "robust-filter") return ObjectiveKind::kRobustFilter;
    throw invalid_field(field_ref("objective"), text, "must be nominal, robust or robust-filter");
}

std::string objective_kind_name(ObjectiveKind k) {
    if (k == ObjectiveKind::kRobustFilter) return "robust-filter";
    return k == ObjectiveKind::kRobust ? "robust" : "nominal";
}

std::pair<int, int> parse_holes_range(const std::string& text) {
    const auto whole_int = [&](const std::string& t, int& v) {
        if (t.empty() || t.size() > 9) return false;
        for (const char c : t)
            if (c < '0' || c > '9') return false;
        v = std::stoi(t);
        return true;
    };
    const std::size_t dots = text.find("..");
    int a = 0, b = 0;
    if (dots == std::string::npos) {
        if (!whole_int(text, a) || a < 1)
            throw invalid_field(field_ref("holes"), text,
                                "must be a pinhole count K >= 1 or a range A..B");
        return {a, 0};
    }
    if (!whole_int(text.substr(0, dots), a) || !whole_int(text.substr(dots + 2), b)) {
        throw invalid_field(field_ref("holes"), text,
                            "a range must be A..B with whole numbers A and B");
    }
    if (a < 1) throw invalid_field(field_ref("holes"), text, "the range must start at A >= 1");
    if (a > b) throw invalid_field(field_ref("holes"), text, "the range A..B must have A <= B");
    return {a, b};
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
    throw invalid_field(field_ref("keep_out"), spec, "expected none or border");
}

void SearchPipelineOptions::validate() const {
    pinmask::validate(tmpl.pattern);
    const std::string holes_text =
        std::to_string(holes) + (max_holes > 0 ? ".." + std::to_string(max_holes) : "");
    if (holes < 1) throw invalid_field(field_ref("holes"), holes_text, "must be >= 1");
    if (max_holes != 0 && max_holes < holes)
        throw invalid_field(field_ref("holes"), holes_text, "the range A..B must have A <= B");
    const PackingUpperBound bound =
        packing_upper_bound(tmpl.pattern.n, tmpl.pattern.min_spacing_cells);
    if (std::max(holes, max_holes) > bound.count) {
        throw invalid_field(field_ref("holes"), holes_text,
                            "the spacing rule (" + std::to_string(tmpl.pattern.min_spacing_cells) +
                                " cells) allows at most " + std::to_string(bound.count) +
                                " pinholes on the " + std::to_string(tmpl.pattern.n) + " x " +
                                std::to_string(tmpl.pattern.n) + " grid (" + bound.reason + ")");
    }
    search.validate();
    islands.validate();
    pinmask::validate(noise);
    prior.validate();
    weights.validate();
    if (weights.depth > 0.0) {
        depth_range.validate();
        if (noise.kind != NoiseKind::kPhoton) {
            throw invalid_field(field_ref("weights.depth"), format_number(weights.depth),
                                "the depth term's Cramer-Rao bound needs the photon model (" +
                                    field_ref("photons") + "), not Gaussian noise at an SNR");
        }
    }
    keep_out_cells(keep_out, tmpl.pattern.n);
    for (const SceneSpec& s : rerank_scenes) {
        if (s.kind == SceneKind::kNatural && prior.kind == PriorKind::kNatural) {
            throw invalid_field(field_ref("rerank_scenes"), "natural",
                                "the search prior is built from natural scenes; re-ranking must "
                                "use scenes the search did not see");
        }
    }
    robust.validate(tmpl.camera.pinhole_m);
    if (objective != ObjectiveKind::kNominal) {
        if (!robust.any()) {
            throw invalid_field(field_ref("objective"), objective_kind_name(objective),
                                "needs " + field_ref("robust") +
                                    " with at least one non-zero error (size, jitter or missing)");
        }
        if (!(weights.analytic_wiener > 0.0)) {
            throw invalid_field(field_ref("objective"), objective_kind_name(objective),
                                "needs the analytic Wiener term (" +
                                    field_ref("weights.analytic_wiener") + " > 0)");
        }
    }
    if (rank_by == RankBy::kTv && (rerank_scenes.empty() || !rerank_tv)) {
        throw invalid_field(field_ref("rank_by"), "tv",
                            "needs the TV re-ranking (not with " + field_ref("no_rerank") + " or " +
                                field_ref("no_rerank_tv") + ")");
    }
}

std::string objective_figure_name(const SearchPipelineOptions& o) {
    if (!(o.weights.analytic_wiener > 0.0)) return "";
    if (o.objective == ObjectiveKind::kNominal) return analytic_figure_name(o.filter);
    return robust_figure_name(o.filter, o.objective == ObjectiveKind::kRobustFilter
                                            ? RobustObjectiveDecoder::kRobustFilter
                                            : RobustObjectiveDecoder::kDesignFilter);
}

SearchPipelineSummary run_search_pipeline(const SearchPipelineOptions& o,
                                          const std::atomic<bool>* cancel,
                                          const PipelineProgress& progress,
                                          const PipelinePhase& setup_phase) {
    o.validate();
    const auto t0 = Clock::now();
    const bool timed = o.search.time_budget_s > 0.0 && o.search.max_evaluations == 0;
    SearchPipelineSummary out;
    out.planned_s = timed ? o.search.time_budget_s : 0.0;

    const int n = o.tmpl.pattern.n, ppc = o.tmpl.psf.pixels_per_cell, m = n * ppc;
    check_psf_memory(n, ppc, 4, 2);
    // Set-up phases are named as they start (they can take seconds at large periods).
    const auto phase = [&](const std::string& name) {
        if (setup_phase) setup_phase(name);
    };
    phase("building the kernel and the scene prior");
    const Kernel kernel = mask_kernel(o.tmpl);
    out.kernel_resolved = kernel_model_name(kernel.model);
    const ComplexPlane kernel_otf = expand_half_spectrum(kernel_spectrum(kernel, n, ppc), m);
    std::shared_ptr<const AnalyticWienerModel> model;
    std::shared_ptr<const RobustWienerModel> robust_model;
    out.prior_description = o.prior.description();
    const bool robust_objective = o.objective != ObjectiveKind::kNominal;
    if (o.weights.analytic_wiener > 0.0 || o.robust.any()) {
        ScenePrior prior = make_scene_prior(o.prior, m);
        out.prior_relevance = prior_relevance(prior);
        if (o.robust.any())
            robust_model = std::make_shared<RobustWienerModel>(o.tmpl, o.robust, prior, o.noise);
        if (o.weights.analytic_wiener > 0.0 && !robust_objective)
            model = std::make_shared<AnalyticWienerModel>(kernel_otf, std::move(prior), o.noise);
    }
    out.objective_figure = objective_figure_name(o);
    std::unique_ptr<SearchObjective> inner;
    if (robust_objective)
        inner = std::make_unique<RobustObjective>(o.weights, robust_model, o.filter,
                                                  o.objective == ObjectiveKind::kRobustFilter
                                                      ? RobustObjectiveDecoder::kRobustFilter
                                                      : RobustObjectiveDecoder::kDesignFilter);
    else
        inner = std::make_unique<MaskObjective>(o.weights, model, o.filter);
    if (o.weights.depth > 0.0) {
        phase("building the depth term's per-cell Fisher information");
        auto table = std::make_shared<const DepthCellTable>(o.tmpl, o.noise, o.depth_range,
                                                            o.search.threads);
        inner = std::make_unique<DepthTermObjective>(std::move(inner), std::move(table),
                                                     o.weights.depth);
    }
    const PipelineObjective objective(*inner, pattern_frequencies_passed(kernel_otf, n),
                                      !o.allow_spectral_zeros);

    SearchOptions so = o.search;
    so.keep_out = keep_out_cells(o.keep_out, n);
    RandomSparseOptions ro;
    ro.n = n;
    ro.holes = o.holes;
    ro.min_spacing_cells = o.tmpl.pattern.min_spacing_cells;
    ro.tiles_rows = o.tmpl.pattern.tiles_rows;
    ro.tiles_cols = o.tmpl.pattern.tiles_cols;
    if (o.max_holes > 0) {
        so.min_holes = o.holes;
        so.max_holes = o.max_holes;
    }
    // With a K range each start draws K uniformly in it; when the random family cannot place
    // that many (near the packing limit) K halves its distance to A until it can (A itself
    // failing is the user's error, raised as is). Annealing can still add pinholes up to B.
    const auto sample = [&](std::mt19937_64& rng) {
        if (o.max_holes == 0) return sample_pattern(ro, so.keep_out, o.keep_out, rng);
        RandomSparseOptions r = ro;
        r.holes = std::uniform_int_distribution<int>(o.holes, o.max_holes)(rng);
        for (;;) {
            try {
                return sample_pattern(r, so.keep_out, o.keep_out, rng);
            } catch (const InvalidInput&) {
                if (r.holes == o.holes) throw;
                r.holes = o.holes + (r.holes - o.holes) / 2;
            }
        }
    };
    std::mt19937_64 probe_rng(o.search.seed);  // fail fast on infeasible requests
    const Pattern probe = sample(probe_rng);

    if (!o.rerank_scenes.empty()) phase("building the re-rank scenes");
    Reranker rr;
    rr.noise = o.noise;
    rr.tv = o.rerank_tv;
    rr.rank_by = o.rank_by;
    rr.sim.seed = o.search.seed;
    rr.sim.wiener_nsr = {true, 0.01};
    rr.sim.tv_lambda = {o.rank_by == RankBy::kTv, 1e-3};
    // The scene list grows with the input (a configuration may list 30,000 scenes): charged to
    // the process-wide budget before a scene is made, and held for the run. Five m x m planes a
    // scene: the scene, the timing copy of the re-ranker, and what the simulated decodes keep per
    // scene (measured: 30,000 scenes of 128 x 128 passed 19 GB uncharged, 4.9 planes a scene).
    const MemoryReservation scenes_held(
        5.0 * double(o.rerank_scenes.size()) * double(m) * double(m) * sizeof(double),
        std::to_string(o.rerank_scenes.size()) + " re-rank scenes of " + std::to_string(m) + " x " +
            std::to_string(m));
    for (const SceneSpec& s : o.rerank_scenes) {
        rr.scenes.push_back({scene_name(s), make_scene(s, m, m)});
        out.rerank_scene_names.push_back(rr.scenes.back().name);
    }

    // Time one re-ranking (on the probe pattern, TV with a fixed weight) to reserve its share
    // of the budget; a tuned TV weight costs kTunedDecodesPerScene times the fixed one.
    double one_rerank_s = 0.0;
    if (timed && !rr.scenes.empty()) {
        phase("timing one re-ranking");
        RankedMask trial;
        trial.mask = o.tmpl;
        trial.mask.pattern = probe;
        Reranker fixed = rr;
        fixed.tv = false;
        auto r0 = Clock::now();
        fixed.apply(trial);
        one_rerank_s = seconds_since(r0);
        if (rr.tv) {
            fixed.tv = true;
            fixed.sim.tv_lambda = {false, 1e-3};
            r0 = Clock::now();
            fixed.apply(trial);
            const double tv_s = std::max(0.0, seconds_since(r0) - one_rerank_s);
            one_rerank_s += rr.sim.tv_lambda.tuned ? kTunedDecodesPerScene * tv_s : tv_s;
        }
        // When not even one re-ranking fits in the largest share, none is reserved (the search
        // gets the whole budget and the summary says 0 were re-ranked).
        const double share = kMaxRerankShare * o.search.time_budget_s;
        out.rerank_reserved_s = kRerankMargin * one_rerank_s > share
                                    ? 0.0
                                    : std::min(share, kRerankMargin * one_rerank_s * o.search.top);
    }
    if (timed) {
        so.time_budget_s =
            std::max(0.01 * o.search.time_budget_s,
                     o.search.time_budget_s - seconds_since(t0) - out.rerank_reserved_s);
    }
    const auto s0 = Clock::now();
    LocalComm one_process;
    RankComm& comm = o.comm ? *o.comm : one_process;
    phase("starting the chains");
    // The rate counts from the first logged row with an evaluation on: the chains' own set-up
    // (sampling, their first evaluation's tables) is not search throughput.
    std::optional<SearchLogRow> first_row;
    out.search = run_island_search(
        comm, objective, so, sample, o.islands, cancel,
        [&](const SearchLogRow& row, double fraction) {
            if (!progress) return;
            if (!first_row && row.evaluations > 0) first_row = row;
            std::ostringstream t;
            t.precision(4);
            if (!first_row) {
                t << "setting up the chains, " << static_cast<int>(row.seconds) << " s";
            } else {
                const double dt = row.seconds - first_row->seconds;
                t << "best " << row.best_objective << ", ";
                if (dt > 0)
                    t << (row.evaluations - first_row->evaluations) / dt << " evals/s";
                else
                    t << "first evaluation after " << first_row->seconds << " s";
                t << ", " << static_cast<int>(row.seconds) << " s";
            }
            progress("search", fraction, t.str());
        });
    out.search_s = seconds_since(s0);
    out.termination = out.search.termination;
    if (comm.rank() != 0) {  // rank 0 holds every rank's chains and alone re-ranks and writes
        out.used_s = seconds_since(t0);
        return out;
    }
    if (out.search.ranked.empty()) {
        throw RuntimeFailure(
            out.search.evaluations == 0
                ? "search stopped before any evaluation"
                : "search found no candidate: every one of " +
                      std::to_string(out.search.evaluations) +
                      " patterns had a spectral zero where the kernel passes light (rejected; " +
                      field_ref("allow_spectral_zeros") + " keeps them, flagged)");
    }

    const std::vector<std::uint8_t> passed = pattern_frequencies_passed(kernel_otf, n);
    const auto ranked_mask = [&](const Candidate& c) {
        RankedMask r;
        r.mask = o.tmpl;
        r.mask.pattern = c.pattern;
        r.mask.pattern.pinholes = sorted_pinholes(c.pattern);
        r.mask.provenance.seed = o.search.seed;
        r.mask.provenance.generator = o.generator;
        r.mask.provenance.family =
            std::string("search:") +
            (o.search.strategy == SearchStrategy::kRandom ? "random" : "anneal");
        r.mask.provenance.scores = c.terms;
        r.mask.provenance.objective_figure = out.objective_figure;
        if (robust_model && !robust_objective) {
            r.mask.provenance
                .scores[robust_figure_name(o.filter, RobustObjectiveDecoder::kDesignFilter)] =
                robust_model->evaluate(pattern_spectrum(c.pattern), o.filter).psnr_db;
        }
        r.objective = c.objective;
        r.sim_wiener_psnr_db = r.sim_tv_psnr_db = NAN;
        const SpectralZero z = find_spectral_zero(pattern_spectrum(c.pattern), passed);
        r.spectral_zero = z.found;
        r.spectral_zero_message = z.message();
        if (z.found) r.mask.provenance.scores["spectral_zero"] = 1.0;
        return r;
    };
    for (const Candidate& c : out.search.ranked) out.ranked.push_back(ranked_mask(c));
    for (const Candidate& c : out.search.best_per_holes)
        out.best_per_holes.push_back(ranked_mask(c));
    if (model) {  // the best any pattern with each K could reach (one bound per distinct K)
        const ObjectiveBoundModel bounds(model, n);
        std::map<int, double> by_k;
        for (auto* list : {&out.ranked, &out.best_per_holes})
            for (RankedMask& r : *list) {
                ObjectiveBoundOptions bo;
                bo.holes = static_cast<int>(r.mask.pattern.pinholes.size());
                auto it = by_k.find(bo.holes);
                if (it == by_k.end()) it = by_k.emplace(bo.holes, bounds.bound(bo).psnr_db).first;
                r.upper_bound_psnr_db = it->second;
            }
    }

    const auto r0 = Clock::now();
    const bool interrupted = cancel && cancel->load();
    if (!rr.scenes.empty() && !interrupted) {
        for (std::size_t i = 0; i < out.ranked.size(); ++i) {
            if (cancel && cancel->load()) break;
            const double estimate = i == 0 ? one_rerank_s : seconds_since(r0) / i;
            // The first candidate is always re-ranked (its time was reserved); the rest while
            // the budget lasts.
            if (timed && i > 0 && seconds_since(t0) + estimate > o.search.time_budget_s) break;
            rr.apply(out.ranked[i]);
            ++out.reranked;
            if (progress) {
                progress(
                    "rerank", static_cast<double>(i + 1) / out.ranked.size(),
                    "re-ranked " + std::to_string(i + 1) + "/" + std::to_string(out.ranked.size()));
            }
        }
        // Re-ranked candidates first (they are a prefix: re-ranked in search order), ordered by
        // optimize/search/rerank_order: the objective's order unless the simulated PSNR of the
        // chosen decoder tells two apart beyond its standard error; the rest after, in search
        // order. The robust objective keeps its own order (the simulations use the nominal PSF).
        if (!robust_objective && out.reranked > 1) {
            std::vector<std::vector<double>> psnr;
            for (int i = 0; i < out.reranked; ++i) psnr.push_back(out.ranked[i].sim_scene_psnr_db);
            const std::vector<std::size_t> order = rerank_order(psnr);
            std::vector<RankedMask> sorted;
            for (std::size_t i = 0; i < order.size(); ++i) {
                if (order[i] != i) ++out.reordered;
                sorted.push_back(std::move(out.ranked[order[i]]));
            }
            std::move(sorted.begin(), sorted.end(), out.ranked.begin());
        }
    }
    out.rerank_s = seconds_since(r0);
    out.used_s = seconds_since(t0);
    return out;
}

}  // namespace pinmask
