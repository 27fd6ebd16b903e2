// Progress of an iterative decode on stderr. Nothing for its first 2 s (most decodes end
// sooner); then a bar on a terminal, or a plain line at once and every 5 s when stderr is a pipe
// or a file (cli/outputs/progress). Each says the iterations done over all channels against the
// most the run may take, the seconds so far, and the time left if every iteration runs (the
// stopping rule may end it sooner): the solvers count iterations as they finish them
// (IterativeOptions::iterations_done), which needs no ground truth.
#pragma once

#include <atomic>
#include <functional>

namespace pinmask::cli {

// Runs work() on a second thread while this one reports `done` against `total`; returns when
// work() has, rethrowing what it threw. With show false (--quiet, a closed-form method) work()
// runs on this thread.
void run_with_decode_progress(long long total, bool show, const std::atomic<long long>& done,
                              const std::function<void()>& work);

}  // namespace pinmask::cli
