#include "design/pattern/generate_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/image/image_io.hpp"
#include "design/pattern/exclusion_grid.hpp"
#include "design/pattern/mura.hpp"
#include "design/pattern/random_sparse.hpp"

namespace pinmask {
namespace {

// The paper and mura families fix some of the geometry: a field given with another value is an
// error rather than silently ignored.
void require_unset_or(bool was_given, const char* field, double given, double fixed,
                      const std::string& why) {
    if (was_given && given != fixed) {
        std::ostringstream v;
        v << given;
        throw invalid_field(field_ref(field), v.str(), why);
    }
}

}  // namespace

GeneratedPattern generate_pattern(const GeneratePatternOptions& o) {
    o.validate();
    const Family family = o.family;
    const GeneratePatternOptions& g = o;
    std::size_t violations = 0;
    std::mt19937_64 rng(o.seed);
    Pattern p;
    if (family == Family::kPaper) {
        const std::string why =
            "the paper family fixes n = 16, K = 20, 2 x 2 tiles, spacing 2 "
            "(use " +
            field_ref("family") + " random for other geometries)";
        require_unset_or(g.grid_given, "grid", g.grid, kPaperGrid, why);
        require_unset_or(g.holes_given, "holes", g.holes, kPaperHoles, why);
        require_unset_or(g.tiles_given, "tiles", g.tiles, kPaperTiles, why);
        require_unset_or(g.spacing_given, "spacing", g.spacing, kPaperSpacingCells, why);
        p = paper_pattern(rng);
    } else if (family == Family::kRandom) {
        RandomSparseOptions r;
        r.n = g.grid;
        r.holes = g.holes;
        r.min_spacing_cells = g.spacing;
        r.tiles_rows = g.tiles;
        r.tiles_cols = g.tiles;
        r.max_attempts = o.attempts;
        p = random_sparse_pattern(r, rng);
    } else {
        if (g.tiles < 1)
            throw invalid_field(field_ref("tiles"), std::to_string(g.tiles), "must be >= 1");
        p = mura_pattern(g.grid, g.spacing, g.tiles, g.tiles);
        const int open = static_cast<int>(p.pinholes.size());
        require_unset_or(g.holes_given, "holes", g.holes, open,
                         "a MURA of order " + std::to_string(g.grid) +
                             " has (p^2 - 1) / 2 = " + std::to_string(open) + " pinholes");
    }
    violations = count_spacing_violations(p);
    GridSpacing grid;
    std::string closest;
    if (o.pinhole_m > 0 && o.pinhole_m <= kMaxGridPitchM) {  // beyond: no layout exists
        // The same rule on the grid pitch, in the words export and check use.
        grid = spacing_on_grid(p, o.pinhole_m, o.fab_grid_nm);
        violations = std::max(violations, grid.violations);
        if (grid.violations > 0)
            closest = " (closest: centres " + um_text(grid.closest_nm) + " apart < " +
                      um_text(grid.limit_nm) + ", the rule " +
                      spacing_rule_text(p.min_spacing_cells, grid.pitch_nm, grid.grid_nm) + ")";
    }
    if (violations > 0 && !o.allow_violations) {
        std::ostringstream v;
        v.precision(10);  // a rule a grid step above a whole number of cells stays readable
        v << p.min_spacing_cells;
        throw invalid_field(field_ref("spacing"), v.str(),
                            "the " + family_name(family) + " pattern of order " +
                                std::to_string(p.n) + " has " + std::to_string(violations) +
                                " pinhole pair(s) closer than that on the torus" + closest +
                                "; pass " + field_ref("allow_violations") +
                                " to write it anyway (the file records "
                                "spacing_violations_allowed), or lower " +
                                field_ref("spacing"));
    }
    return {p, violations, grid};
}

// Bounds that later commands enforce, checked here so generate never writes a mask they refuse.
void GeneratePatternOptions::validate() const {
    if (attempts < 1)
        throw invalid_field(field_ref("attempts"), std::to_string(attempts), "must be >= 1");
    const GeneratePatternOptions& g = *this;
    if (g.tiles < 1 || g.tiles > kMaxTiles) {
        throw invalid_field(field_ref("tiles"), std::to_string(g.tiles),
                            "must be between 1 and " + std::to_string(kMaxTiles) +
                                " (the largest tiling the mask reader and export accept)");
    }
    if (g.grid < 1 || g.grid > kMaxGrid) {
        throw invalid_field(field_ref("grid"), std::to_string(g.grid),
                            "must be between 1 and " + std::to_string(kMaxGrid));
    }
}

// The PSF of one period is (grid x pixels per cell)^2 samples: it must be an image that psf,
// simulate and decode can hold (kMaxImageSamples), else generate would write a mask they refuse.
void check_period_psf_size(int ppc, int grid, bool given) {
    const double side = double(ppc) * grid;
    if (side * side <= double(kMaxImageSamples)) return;
    const auto max_side = static_cast<long long>(std::sqrt(double(kMaxImageSamples)));
    throw invalid_field(
        given ? field_ref("pixels_per_cell") : "pixels per cell (design value from the camera)",
        std::to_string(ppc),
        "the PSF of one period would be " + std::to_string(static_cast<long long>(side)) +
            " px wide (grid " + std::to_string(grid) +
            " x pixels per cell); psf, simulate and decode hold at most " +
            std::to_string(kMaxImageSamples) + " samples (kMaxImageSamples), " +
            std::to_string(max_side) + " px per side: at most " + std::to_string(max_side / grid) +
            " pixels per cell at grid " + std::to_string(grid));
}

}  // namespace pinmask
