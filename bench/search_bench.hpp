// Search throughput (the objective after one move reads optimize/metrics/aliased_wiener tables,
// O(n^2)): incremental single-pinhole moves (two plane waves on P^, O(K) on the autocorrelation,
// O(1) legality) against full re-evaluation of the same quantities from scratch (FFT of the
// occupancy and inverse FFT of |P^|^2), timed in the same run.
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

// The search objective after one move: a legal single-pinhole move plus the analytic
// Wiener objective (optimize/search/mask_objective, optimal filter, natural prior, Gaussian 30 dB)
// on an n x n pattern of ppc pixels per cell (paper camera, auto kernel), against the full
// evaluation of the same pattern as a reference timed in the same run (PSF synthesis and an
// m x m FFTW r2c transform, m = n ppc). per_cell_rate = moves/s x n^2: constant when the cost
// scales as n^2 only.
struct ObjectiveBenchRecord {
    int n = 0, pixels_per_cell = 0, holes = 0;
    double moves_per_second = 0.0;
    double full_evals_per_second = 0.0;
    double per_cell_rate = 0.0;
};
std::vector<ObjectiveBenchRecord> bench_objective(const std::vector<std::pair<int, int>>& configs,
                                                  double seconds, std::uint64_t seed);

}  // namespace pinmask
