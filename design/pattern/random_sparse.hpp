// The random sparse family: K pinholes on the n x n torus under the spacing rule
// (design/pattern/pattern.hpp), placed by random sequential choice: each pinhole is drawn uniformly
// from the cells still free (not closer than the spacing to any chosen pinhole); when no cell
// is left before K are placed, the attempt restarts, a bounded number of times.
#pragma once

#include <random>

#include "design/pattern/pattern.hpp"

namespace pinmask {

struct RandomSparseOptions {
    int n = 16;                      // grid size, 1..kMaxGrid
    int holes = 20;                  // K >= 1
    double min_spacing_cells = 2.0;  // s, finite >= 0
    int tiles_rows = 2;              // recorded in the Pattern
    int tiles_cols = 2;
    int max_attempts = 20;  // restarts before giving up (each is O(n^2 + K s^2) at worst)
};

// A valid pattern (pinholes in canonical order) drawn with rng. Throws InvalidInput naming
// `holes` when K pinholes cannot be placed: immediately when K exceeds the proven upper bound
// (design/pattern/packing_bound.hpp), else after max_attempts; the message gives the upper bound
// and its argument, the size of a verified lattice placement, and the most the random search
// placed. Time O(max_attempts (K s^2 + n^2)) at worst, usually O(K s^2); memory O(n^2).
Pattern random_sparse_pattern(const RandomSparseOptions& options, std::mt19937_64& rng);

}  // namespace pinmask
