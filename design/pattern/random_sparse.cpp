#include "design/pattern/random_sparse.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/limits/resource_limits.hpp"
#include "design/pattern/exclusion_grid.hpp"
#include "design/pattern/packing_bound.hpp"

namespace pinmask {
namespace {

void check_options(const RandomSparseOptions& o) {
    if (o.n < 1 || o.n > kMaxGrid) {
        throw invalid_field("n", std::to_string(o.n),
                            "must be between 1 and " + std::to_string(kMaxGrid));
    }
    if (o.holes < 1)
        throw invalid_field(field_ref("holes"), std::to_string(o.holes), "must be >= 1");
    if (!std::isfinite(o.min_spacing_cells) || o.min_spacing_cells < 0.0) {
        throw invalid_field("min_spacing_cells", std::to_string(o.min_spacing_cells),
                            "must be finite and >= 0");
    }
    if (o.tiles_rows < 1 || o.tiles_cols < 1) {
        throw invalid_field("tiles",
                            std::to_string(o.tiles_rows) + "x" + std::to_string(o.tiles_cols),
                            "both must be >= 1");
    }
    if (o.max_attempts < 1) {
        throw invalid_field("max_attempts", std::to_string(o.max_attempts), "must be >= 1");
    }
}

// One random sequential attempt: each pinhole uniform among the free cells (a uniform rank
// into the free cells, found through the grid's Fenwick index); stops at K pinholes or when no
// cell is free.
std::vector<Cell> attempt(int n, int holes, double s, std::mt19937_64& rng) {
    ExclusionGrid grid(n, s, ExclusionGrid::Index::kRank);
    std::vector<Cell> chosen;
    chosen.reserve(static_cast<std::size_t>(holes));
    while (chosen.size() < static_cast<std::size_t>(holes) && grid.free_count() > 0) {
        std::uniform_int_distribution<std::size_t> rank(0, grid.free_count() - 1);
        const Cell c = grid.cell_of(grid.nth_free(rank(rng)));
        chosen.push_back(c);
        grid.place(c);
    }
    return chosen;
}

[[noreturn]] void fail(const RandomSparseOptions& o, std::size_t reached, int attempts,
                       const PackingUpperBound& upper) {
    const LatticePlacement lattice = lattice_placement(o.n, o.min_spacing_cells);
    std::ostringstream msg;
    msg << "cannot place " << o.holes << " pinholes on the " << o.n << " x " << o.n
        << " torus at spacing " << o.min_spacing_cells << " cells. At most " << upper.count
        << " fit (" << upper.reason << "); a verified lattice placement holds "
        << lattice.cells.size() << " (" << lattice.description << "); ";
    if (attempts == 0) {
        msg << "random placement was not tried";
    } else {
        msg << "random sequential placement reached " << reached << " (best of " << attempts
            << " attempt" << (attempts == 1 ? "" : "s") << ")";
    }
    msg << ". Ask for fewer pinholes, a smaller spacing or a larger grid";
    throw invalid_field(field_ref("holes"), std::to_string(o.holes), msg.str());
}

}  // namespace

Pattern random_sparse_pattern(const RandomSparseOptions& o, std::mt19937_64& rng) {
    check_options(o);
    const double cells = static_cast<double>(o.n) * o.n;
    // Exclusion bits and their Fenwick index (well under 1 byte per cell) plus the chosen cells.
    check_memory(cells + 8.0 * o.holes, "random placement on a " + std::to_string(o.n) + " x " +
                                            std::to_string(o.n) + " torus");
    const PackingUpperBound upper = packing_upper_bound(o.n, o.min_spacing_cells);
    if (o.holes > upper.count) {
        // Hopeless: one attempt only, to report how far random placement gets.
        const std::size_t reached =
            upper.count == 0 ? 0 : attempt(o.n, o.holes, o.min_spacing_cells, rng).size();
        fail(o, reached, upper.count == 0 ? 0 : 1, upper);
    }
    std::size_t best = 0;
    for (int a = 0; a < o.max_attempts; ++a) {
        std::vector<Cell> chosen = attempt(o.n, o.holes, o.min_spacing_cells, rng);
        if (chosen.size() == static_cast<std::size_t>(o.holes)) {
            Pattern p;
            p.n = o.n;
            p.pinholes = std::move(chosen);
            p.pinholes = sorted_pinholes(p);
            p.tiles_rows = o.tiles_rows;
            p.tiles_cols = o.tiles_cols;
            p.min_spacing_cells = o.min_spacing_cells;
            return p;
        }
        best = std::max(best, chosen.size());
    }
    fail(o, best, o.max_attempts, upper);
}

}  // namespace pinmask
