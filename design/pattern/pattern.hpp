// A cyclic pinhole pattern: an n x n torus of cells (cell side = pinhole side d), K of them open.
// The mask is the pattern tiled tiles_rows x tiles_cols times, so distances are measured on the
// torus: the spacing rule holds across the seams of the tiled mask.
#pragma once

#include <compare>
#include <cstdint>
#include <string>
#include <vector>

namespace pinmask {

inline constexpr int kMaxGrid = 4096;
// Largest tile count per axis: a mask of more periods is beyond what export lays out (its
// polygons are refused by the memory bound long before) and than any sensor sees (a period is
// at least one pixel per cell).
inline constexpr int kMaxTiles = 1024;

// One cell of the torus, 0 <= row, col < n.
struct Cell {
    int row = 0;
    int col = 0;
    auto operator<=>(const Cell&) const = default;
};

struct Pattern {
    int n = 16;
    std::vector<Cell> pinholes;
    int tiles_rows = 2;
    int tiles_cols = 2;
    // Pinhole centres at least this many cell sides apart (Euclidean, on the torus).
    double min_spacing_cells = 2.0;
};

// Shortest distance between the centres of a and b on the n x n torus, in cells.
double torus_distance_cells(Cell a, Cell b, int n);

// Distances within this of the rule count as meeting it (cell coordinates are integers, so this
// only absorbs rounding in the square root).
inline constexpr double kSpacingTolerance = 1e-9;

// A pair closer than the rule. a == b marks a pinhole too close to its own periodic copy
// (n < min_spacing on a tiled mask).
struct SpacingViolation {
    Cell a;
    Cell b;
    double distance_cells;
};

// Every pair of pinholes closer than min_spacing_cells on the torus. O(K * s^2) with an
// occupancy grid, s = ceil(min_spacing_cells). Pinholes must be inside the grid.
std::vector<SpacingViolation> spacing_violations(const Pattern& p);

// Structural checks: 1 <= n <= kMaxGrid, tiles >= 1, spacing finite and >= 0, every pinhole
// inside the grid, no duplicates. Throws InvalidInput naming the problem. The spacing rule is
// checked too unless allow_spacing_violations.
void validate(const Pattern& p, bool allow_spacing_violations = false);

// Pattern as an n x n 0/1 occupancy array, row-major (index row * n + col).
std::vector<std::uint8_t> occupancy(const Pattern& p);

// Pinholes in canonical (row, col) order.
std::vector<Cell> sorted_pinholes(const Pattern& p);

}  // namespace pinmask
