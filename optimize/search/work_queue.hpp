// A dynamic work queue over the ranks of a RankComm (master/worker):
// rank 0 hands out item indices one at a time to whichever worker rank asks,
// and runs items itself in a second thread that takes indices from the same
// counter (its main thread alone calls the comm, as MPI_THREAD_FUNNELED
// requires). Workers send each result back as bytes. On one rank (LocalComm, a
// plain run) the items run in order on the calling thread. Used by sweeps.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "optimize/search/rank_comm.hpp"

namespace pinmask {

// Computes item `index`; throwing marks the item failed with the exception's
// message.
using WorkItem = std::function<std::string(int index)>;
// Rank 0: item `index` finished (done items so far, of count). Called from one
// thread at a time.
using WorkDone = std::function<void(int done, int count, int index)>;

struct WorkQueueResult {
    std::vector<std::string> results;    // rank 0: by index (empty after a failure); others: empty
    int failed_index = -1;               // the lowest failed item seen (rank 0), -1 when none
    std::string failure;                 // its message
    bool failure_invalid_input = false;  // it was InvalidInput (exit 2), else a runtime failure
};

// Message tags of the queue (below the comm's reserved tags).
inline constexpr int kWorkReadyTag = 11;   // worker -> 0: first request (no payload)
inline constexpr int kWorkResultTag = 12;  // worker -> 0: index + outcome; asks for the next
inline constexpr int kWorkAssignTag = 13;  // 0 -> worker: index, or -1: stop

// Runs items 0..count-1 (see above). Every rank calls it with the same count.
// After a failure no new item starts; items already running finish.
WorkQueueResult run_work_queue(RankComm& comm, int count, const WorkItem& work,
                               const WorkDone& done = {});

}  // namespace pinmask
