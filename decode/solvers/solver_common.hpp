// Shared plumbing of the iterative solvers of decode/ (tv_l2, tvqc, richardson_lucy): the
// stopping rule, the clock of the iteration records, and option checks.
//
// Stopping rule: after iteration k >= 1 a solver stops when ||x_k - x_{k-1}||_2 <= tolerance *
// ||x_k||_2 (relative change of x; 0 / 0 counts as 0) or when k = max_iterations.
#pragma once

#include <atomic>
#include <chrono>

#include "core/image/image.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"

namespace pinmask {

// Options every iterative solver shares.
struct IterativeOptions {
    int max_iterations = 200;    // >= 0; 0 returns the starting point
    double tolerance = 1e-4;     // >= 0; relative change of x that ends the iteration
    bool record_history = true;  // fill DecodeResult::history (costs an objective per iteration)
    // When set, polled once per iteration: once true, the solver ends after the iteration it is
    // in, as if it had reached max_iterations, and sets DecodeResult::interrupted (Ctrl-C in
    // `pinmask decode`: the estimate so far is written).
    const std::atomic<bool>* stop = nullptr;
    // When set, every finished iteration adds 1 (over all channels decoded with these options),
    // so a face can report the iteration while the solver runs (Python's decode progress).
    std::atomic<long long>* iterations_done = nullptr;
};

// True when options.stop is set and raised.
inline bool stop_requested(const IterativeOptions& options) {
    return options.stop != nullptr && options.stop->load(std::memory_order_relaxed);
}

// At the end of an iteration: true when the solver must stop, because its stopping rule holds
// (`converged`: sets result.converged) or options.stop is raised (sets result.interrupted).
inline bool iteration_ends(bool converged, const IterativeOptions& options, DecodeResult& result) {
    if (options.iterations_done != nullptr)
        options.iterations_done->fetch_add(1, std::memory_order_relaxed);
    if (converged) {
        result.converged = true;
        return true;
    }
    if (stop_requested(options)) {
        result.interrupted = true;
        return true;
    }
    return false;
}

// Throws InvalidInput naming max_iterations or tolerance when out of range.
void validate_iterative_options(const IterativeOptions& options);

// Throws InvalidInput (field "warm_start") unless the plane has the working size and is finite.
void check_warm_start(const Plane& warm_start, const ConvGeometry& geometry);

// ||a - b||_2 / ||a||_2, 0 when both are zero, +inf when only a is zero.
double relative_change(const Plane& a, const Plane& b);

// Seconds since construction (steady clock), for IterationRecord::seconds.
class SolverClock {
  public:
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    }

  private:
    std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

}  // namespace pinmask
