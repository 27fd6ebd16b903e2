// `pinmask generate`'s pattern as one library call: a family (random | paper | mura)
// with its geometry rules (paper and mura fix some of the geometry: a field given with another
// value is refused rather than silently ignored), the spacing-rule check, and the bound on the
// PSF size every later command must hold.
#pragma once

#include <cstddef>
#include <cstdint>

#include "design/optics/fab_grid.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/pattern.hpp"

namespace pinmask {

struct GeneratePatternOptions {
    Family family = Family::kRandom;
    int grid = 16;         // n (mura: the prime order p = 4m + 1)
    int holes = 20;        // K
    int tiles = 2;         // tiles per side
    double spacing = 2.0;  // min centre spacing, cells
    // Which geometry fields were given: a family that fixes one refuses another given value.
    bool grid_given = false, holes_given = false, tiles_given = false, spacing_given = false;
    std::uint64_t seed = 1;         // random, paper
    int attempts = 20;              // random, paper: restarts of random sequential placement, >= 1
    bool allow_violations = false;  // else a pattern that breaks the spacing rule is refused
    // The camera's pinhole side: when > 0 the spacing rule is also evaluated on the fabrication
    // grid pitch (design/optics/fab_grid), as export and check evaluate it.
    double pinhole_m = 0.0;
    std::int64_t fab_grid_nm = kDefaultFabGridNm;

    // InvalidInput naming the field, value and rule: attempts >= 1, tiles in 1..kMaxTiles,
    // grid in 1..kMaxGrid (the bounds the mask reader and export accept).
    void validate() const;
};

struct GeneratedPattern {
    Pattern pattern;
    std::size_t spacing_violations = 0;  // > 0 only with allow_violations
    GridSpacing grid;                    // the rule on the grid pitch (pinhole_m > 0)
};

GeneratedPattern generate_pattern(const GeneratePatternOptions& options);

// InvalidInput unless the PSF of one period, (grid x ppc)^2 samples, fits kMaxImageSamples (what
// psf, simulate and decode hold). `given`: ppc was the user's pixels_per_cell (else the design
// value).
void check_period_psf_size(int pixels_per_cell, int grid, bool given);

}  // namespace pinmask
