// Search throughput: incremental single-pinhole moves (two plane waves on P^, O(K) on the
// autocorrelation, O(1) legality) against full re-evaluation of the same quantities from scratch
// (FFT of the occupancy and inverse FFT of |P^|^2), timed in the same run.
#pragma once

#include <cstdint>
#include <vector>

namespace pinmask {

struct SearchBenchRecord {
    int n = 0;
    int holes = 0;
    double moves_per_second = 0.0;       // incremental: legality test + move
    double full_evals_per_second = 0.0;  // spectrum + autocorrelation recomputed from scratch
    double speedup = 0.0;                // moves_per_second / full_evals_per_second
};

// Times each n for about `seconds_per_size` per method on the calling thread (one core).
std::vector<SearchBenchRecord> bench_search(const std::vector<int>& sizes, double seconds_per_size,
                                            std::uint64_t seed);

}  // namespace pinmask
