// The whole `pinmask search` as one library call: sampling with keep-out cells, the
// search (optimize/search/search) on the analytic objective (optimize/search/mask_objective) under
// any noise model and scene prior (optimize/metrics/mask_metrics), the spectral-zero rule, the
// simulated re-ranking of the top candidates on held-out scenes by the chosen decoder, and the
// top-k.
//
// Time budget: with time_budget_s = T everything after validation counts: building
// the model, the search, and the re-ranking. Before searching, one re-ranking of a random
// pattern is timed; the search gets T minus the time reserved for re-ranking top candidates
// (at most half of T), and re-ranking stops early (the rest keep their search order, marked
// not re-ranked) when the next candidate would pass T. The summary reports planned and used.
#pragma once

#include <atomic>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/depth_fisher.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/search/island_search.hpp"
#include "optimize/search/mask_objective.hpp"
#include "optimize/search/rank_comm.hpp"
#include "optimize/search/robust_objective.hpp"
#include "optimize/search/search.hpp"

namespace pinmask {

enum class RankBy { kWiener, kTv };
const std::vector<std::pair<RankBy, std::string>>& rank_by_names();  // wiener, tv
std::string rank_by_name(RankBy r);
RankBy parse_rank_by(const std::string& text);  // InvalidInput naming `rank_by`

// What the analytic Wiener term measures: the design's PSNR, its expected
// PSNR under fabrication errors decoded with the nominal PSF (kRobust), or that expectation with
// the decoder chosen for the errors (kRobustFilter: RobustObjectiveDecoder::kRobustFilter, the
// per-frequency robust filter; optimize/metrics/robust_wiener.hpp).
enum class ObjectiveKind { kNominal, kRobust, kRobustFilter };
ObjectiveKind parse_objective_kind(const std::string& text);  // InvalidInput naming `objective`
std::string objective_kind_name(ObjectiveKind k);             // nominal, robust, robust-filter

struct SearchPipelineOptions {
    Mask tmpl;       // camera, PSF settings, pattern n, tiles, spacing (no pinholes)
    int holes = 20;  // K, >= 1 (with max_holes: the smallest K)
    // Pinhole-count range (`holes` A..B): 0 = K fixed at `holes`; else the search adds
    // and removes pinholes within holes..max_holes and keeps the best mask per K.
    int max_holes = 0;
    SearchOptions search;           // strategy, threads, budgets, seed, top (keep_out set below)
    std::string keep_out = "none";  // none | border
    NoiseModel noise;               // the objective's noise model (Gaussian SNR or photon)
    PriorSpec prior;                // the objective's scene prior
    WienerFilterSpec filter{WienerFilterKind::kOptimal, 0.0};
    ObjectiveWeights weights;
    DepthRange depth_range;  // the depth term's distances (used when weights.depth > 0)
    // kRobust, kRobustFilter: the analytic Wiener term is the expected PSNR under `robust` (which
    // must have an
    // error); the re-ranking then reports its simulated figures without reordering (they are
    // nominal-PSF figures, which would undo the robust choice). With kNominal and errors given,
    // every candidate's robust PSNR is reported beside the nominal one (robust_figure_name).
    ObjectiveKind objective = ObjectiveKind::kNominal;
    FabricationErrors robust;
    bool allow_spectral_zeros = false;     // else patterns with a spectral zero are rejected
    std::vector<SceneSpec> rerank_scenes;  // empty: no re-ranking
    bool rerank_tv = true;                 // also simulate TV when re-ranking
    RankBy rank_by = RankBy::kWiener;      // kTv: TV with lambda tuned per mask decides
    std::string generator = "pinmask search";
    // Several processes: the ranks to spread the chains over (null: this process alone) and
    // the island model's migration and checkpoints (optimize/search/island_search). Only rank 0's
    // summary holds the ranked masks; other ranks return after the search.
    RankComm* comm = nullptr;
    IslandOptions islands;

    // InvalidInput naming the field, value and rule.
    void validate() const;
};

struct RankedMask {
    Mask mask;  // provenance scores hold the objective terms and the simulated figures
    double objective = 0.0;
    double sim_wiener_psnr_db = 0.0;  // NaN when not re-ranked
    double sim_tv_psnr_db = 0.0;      // NaN when not re-ranked or TV skipped
    double tv_lambda = 0.0;           // the TV weight used (tuned with rank_by tv)
    bool reranked = false;
    // Per re-rank scene, the ranking decoder's simulated PSNR (optimize/search/rerank_order's
    // input).
    std::vector<double> sim_scene_psnr_db;
    bool spectral_zero = false;  // only with allow_spectral_zeros
    std::string spectral_zero_message;
    // Upper bound on the analytic MMSE PSNR (analytic_mmse_psnr_db) of ANY pattern with this mask's
    // K under the objective's kernel, prior and noise (optimize/search/objective_bound); NaN
    // without the nominal analytic objective (--objective robust, or no Wiener weight).
    double upper_bound_psnr_db = NAN;
};

struct SearchPipelineSummary {
    std::vector<RankedMask> ranked;  // best first
    // With a pinhole-count range: the best mask at each K the search evaluated, ascending K
    // (objective and analytic terms only: not re-ranked by simulation). Empty otherwise.
    std::vector<RankedMask> best_per_holes;
    SearchSummary search;
    SearchTermination termination = SearchTermination::kTimeBudget;
    std::string kernel_resolved;  // the kernel model used
    double planned_s = 0.0;       // the time budget (0 with an evaluation budget)
    double used_s = 0.0;          // everything: setup, search, re-ranking
    double search_s = 0.0, rerank_s = 0.0;
    double rerank_reserved_s = 0.0;  // time held back from the search for re-ranking
    int reranked = 0;                // candidates re-ranked (the rest: budget or interrupt)
    int reordered =
        0;  // candidates the simulation moved (optimize/search/rerank_order: beyond the SE)
    std::vector<std::string> rerank_scene_names;  // the simulated figures' scenes
    PriorRelevance prior_relevance;  // frequencies the prior makes irrelevant (for --explain)
    std::string prior_description;
    // The scores key of the analytic figure the objective weighs (analytic_figure_name,
    // robust_figure_name); "" without an analytic Wiener weight. Also each mask's
    // provenance.objective_figure.
    std::string objective_figure;
};

// The scores key of the analytic figure the options' objective weighs (analytic_figure_name or
// robust_figure_name of its filter); "" without an analytic Wiener weight.
std::string objective_figure_name(const SearchPipelineOptions& options);

// Progress: (phase "search" | "rerank", fraction 0..1, text). The search's rate counts from its
// first logged row on (the chains' set-up is not throughput).
using PipelineProgress = std::function<void(const std::string&, double, const std::string&)>;
// A set-up phase starting ("building the kernel and the scene prior", "building the re-rank
// scenes", "timing one re-ranking", "starting the chains").
using PipelinePhase = std::function<void(const std::string&)>;

// Runs everything. `cancel` (may be null) stops the search and skips re-ranking; the best so far
// is returned. RuntimeFailure when no candidate was found (e.g. every pattern had a spectral
// zero: the message says so and names --allow-spectral-zeros).
SearchPipelineSummary run_search_pipeline(const SearchPipelineOptions& options,
                                          const std::atomic<bool>* cancel = nullptr,
                                          const PipelineProgress& progress = {},
                                          const PipelinePhase& setup_phase = {});

// "K" or "A..B" (--holes); InvalidInput naming --holes for anything else (A > B, A < 1, junk).
// Returns {A, B} with B = 0 for a single K.
std::pair<int, int> parse_holes_range(const std::string& text);

// Keep-out cells of a spec (none | border) on an n x n grid; InvalidInput naming --keep-out.
std::vector<Cell> keep_out_cells(const std::string& spec, int n);

}  // namespace pinmask
