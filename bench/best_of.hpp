// The shortest wall-clock time of `repeat` runs of a callable: the benchmarks' figure for a
// step (the minimum is the least disturbed by other work on the machine).
#pragma once

#include <algorithm>
#include <chrono>
#include <limits>

namespace pinmask {

template <class F>
double best_of(int repeat, F&& fn) {
    using Clock = std::chrono::steady_clock;
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < repeat; ++r) {
        const auto t0 = Clock::now();
        fn();
        best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    return best;
}

}  // namespace pinmask
