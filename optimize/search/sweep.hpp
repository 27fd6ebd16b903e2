// Design sweeps: one search (optimize/search/search_pipeline) per design point, the points
// shared among MPI ranks by a dynamic work queue (optimize/search/work_queue) or run in order on
// one process. Each point's result travels as bytes (encode/decode below) and rank 0 rebuilds the
// best mask from the point's own template: the result of a point depends on its options alone
// (its seed included), never on the rank that ran it or the order points finished in.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/search/rank_comm.hpp"
#include "optimize/search/search_pipeline.hpp"

namespace pinmask {

// What a point's search sends back: the best candidate and the run's counters.
struct SweepPointResult {
    Pattern pattern;                       // the best pattern (sorted pinholes)
    std::map<std::string, double> scores;  // its provenance scores (objective terms, simulated)
    double objective = 0.0;
    bool reranked = false;
    std::int64_t evaluations = 0;  // all chains
    std::string kernel_resolved;
};

// The point's result as bytes (native byte order: ranks of one job share a machine type) and
// back. decode_sweep_result throws RuntimeFailure on a truncated or malformed buffer.
std::string encode_sweep_result(const SweepPointResult& r);
SweepPointResult decode_sweep_result(std::string_view bytes);

// Runs one point's search and keeps its best candidate.
SweepPointResult run_sweep_point(const SearchPipelineOptions& options);

// The best mask of a point: the point's template with the result's pattern and provenance.
Mask sweep_best_mask(const SearchPipelineOptions& options, const SweepPointResult& r);

// (points done, points in all, index of the point just done): rank 0's progress.
using SweepProgress = std::function<void(int done, int count, int index)>;

// Runs every point: over the ranks of `comm` when it has more than one (optimize/search/work_queue:
// rank 0 hands out point indices and runs points itself too; workers send results back as bytes),
// else in order. Returns the results in point order on rank 0 and an
// empty vector on the other ranks. The first failing point (lowest index) is rethrown on rank 0
// after every rank stopped; other ranks return empty.
std::vector<SweepPointResult> run_sweep(RankComm& comm,
                                        const std::vector<SearchPipelineOptions>& points,
                                        const SweepProgress& progress = {});

}  // namespace pinmask
