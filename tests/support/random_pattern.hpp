// K distinct random cells on the n x n torus, without the spacing rule (min_spacing_cells 0):
// the patterns of the metric and PSF tests, which do not need the rule.
#pragma once

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "design/pattern.hpp"

namespace pinmask::test {

inline Pattern random_pattern(int n, int holes, unsigned seed) {
    std::vector<int> cells(static_cast<std::size_t>(n) * n);
    std::iota(cells.begin(), cells.end(), 0);
    std::mt19937_64 rng(seed);
    std::shuffle(cells.begin(), cells.end(), rng);
    Pattern p;
    p.n = n;
    p.min_spacing_cells = 0.0;
    for (int i = 0; i < holes; ++i) p.pinholes.push_back({cells[i] / n, cells[i] % n});
    return p;
}

}  // namespace pinmask::test
