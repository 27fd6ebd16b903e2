// K distinct random cells on the n x n torus, without the spacing rule (min_spacing_cells 0):
// the patterns of the metric and PSF tests, which do not need the rule; and the paper-camera
// masks of the robust-figure tests built on them.
#pragma once

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "design/optics/camera.hpp"
#include "design/pattern/mask.hpp"
#include "design/pattern/pattern.hpp"

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

// The paper's camera (design/optics/camera paper_camera) with random_pattern(n, holes, seed), 8 px
// per cell and the given kernel model.
inline Mask random_paper_mask(int n, int holes, unsigned seed, const std::string& kernel = "box") {
    Mask m;
    m.camera = paper_camera();
    m.pattern = random_pattern(n, holes, seed);
    m.psf.pixels_per_cell = 8;
    m.psf.kernel.model = kernel;
    return m;
}

}  // namespace pinmask::test
