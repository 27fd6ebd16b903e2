// Exact union of square cells on a grid, as simple hole-free polygons. Used for full-cell square
// pinholes that touch (only possible when the spacing rule is off, e.g. MURA): the union is
// traced on the cell lattice, so it is exact on any manufacturing grid.
//
// Topology: cells are closed squares, so two diagonal cells touch at a corner. Pieces are the
// edge-connected (4-connected) groups of cells; groups that meet only at a corner stay separate
// polygons sharing that vertex (their union is not a simple polygon). A hole is an
// edge-connected group of empty cells enclosed by the union; the cell rows are cut along the
// top edge of every hole, which provably leaves every piece hole-free and free of
// self-touching vertices (an enclosed empty region of a piece would contain part of an original
// hole whose top row lies on a cut). Pieces with more than max_vertices vertices are cut again
// at their middle row, down to single rows (rectangles).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

// Union of the occupied cells of a rows x cols grid (row-major, row 0 at the top). Cell (r, c)
// spans x_edges[c]..x_edges[c + 1] and y_edges[r + 1]..y_edges[r] (y_edges strictly
// decreasing, x_edges strictly increasing; sizes cols + 1 and rows + 1). Rings are
// counter-clockwise, in row-major order of their first cell. max_vertices >= 4.
std::vector<Ring> union_of_cells(const std::vector<std::uint8_t>& occupied, int rows, int cols,
                                 const std::vector<std::int64_t>& x_edges,
                                 const std::vector<std::int64_t>& y_edges,
                                 std::size_t max_vertices);

}  // namespace pinmask
