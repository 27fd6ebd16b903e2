// The pattern the depth and depthmap benches time: 20 pinholes on 16 x 16 cells under the
// spacing rule s = 2, drawn by design/pattern/random_sparse from a fixed seed (the same pattern
// every run).
#pragma once

#include <random>

#include "design/pattern/pattern.hpp"
#include "design/pattern/random_sparse.hpp"

namespace pinmask {

inline Pattern bench_pattern_16x16_k20() {
    RandomSparseOptions ro;
    ro.n = 16;
    ro.holes = 20;
    ro.min_spacing_cells = 2.0;
    std::mt19937_64 rng(1);
    return random_sparse_pattern(ro, rng);
}

}  // namespace pinmask
