// The search over several processes: an island model on optimize/search/rank_comm.
//   - Each rank runs options.threads chains; rank r's chain c is global chain r * threads + c,
//     seeded from (seed, global chain), so rank 0 of any run is the plain run's chains.
//   - Every migrate_every evaluations per chain (at the chains' next restart boundary,
//     optimize/search/search SearchSegments) each rank sends its best pattern to rank + 1 on a
//     ring; each chain whose best is worse than the received one starts its next annealing restart
//     from it (ties keep their own). On one rank the ring is the rank itself.
//   - Every checkpoint_every evaluations per chain every chain's state is gathered to rank 0,
//     which hands them to `checkpoint` (the caller writes the file).
//   - At the end rank 0 gathers every chain and returns the summary of all of them; other ranks
//     return their own chains' summary.
// With an evaluation budget the result depends only on (seed, ranks, threads, migrate_every):
// boundaries fall at fixed evaluation counts and the exchange is deterministic.
#pragma once

#include <functional>

#include "optimize/search/rank_comm.hpp"
#include "optimize/search/search.hpp"

namespace pinmask {

struct IslandOptions {
    std::int64_t migrate_every = 0;     // evaluations per chain between migrations; 0: none
    std::int64_t checkpoint_every = 0;  // evaluations per chain between checkpoints; 0: none
    // A resumed run: every rank's chains in global order (empty: a fresh run) and the
    // boundaries already passed.
    std::vector<ChainState> resume;
    std::int64_t resume_segment = 0;
    // On rank 0 at each checkpoint: the boundaries passed, the evaluations per chain between
    // boundaries, and every chain's state in global order. May throw (the run then fails).
    std::function<void(std::int64_t segment, std::int64_t every, const std::vector<ChainState>&)>
        checkpoint;

    // InvalidInput naming `migrate_every` / `checkpoint_every`.
    void validate() const;
};

// Evaluations per chain between boundaries: the greatest common divisor of the non-zero periods
// (0 when neither is set).
std::int64_t island_segment_length(const IslandOptions& o);

// The bytes one migration sends from one rank to the next (the encoded best pattern).
Bytes migration_message(const std::vector<ChainState>& states);

SearchSummary run_island_search(RankComm& comm, const SearchObjective& objective,
                                const SearchOptions& options,
                                const std::function<Pattern(std::mt19937_64&)>& sample,
                                const IslandOptions& islands,
                                const std::atomic<bool>* cancel = nullptr,
                                const SearchProgress& progress = {});

}  // namespace pinmask
