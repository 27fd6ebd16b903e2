// The repetition in a layout's polygons, for writers that can say "the same shape again"
// (GDSII structure references and arrays, OASIS repetitions): every polygon as a shape placed
// by translation, and, when the polygons repeat exactly across the mask's tiles, the placements
// of one tile and the tile array. Exact: expand() gives back the polygons (same vertices, same
// order within each ring), or find_repetition reports no tile array.
#pragma once

#include <cstddef>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

struct Placement {
    std::size_t shape = 0;  // index into Repetition::shapes
    PointNm at;             // translation of the shape
};

struct Repetition {
    std::vector<Ring> shapes;           // distinct polygons, first vertex at the origin
    std::vector<Placement> placements;  // one tile's polygons (all of them when cols = rows = 1)
    int cols = 1, rows = 1;             // the tile array (1 x 1: no array)
    std::int64_t pitch_x_nm = 0, pitch_y_nm = 0;  // tile pitch along x and y
    // Polygons the array and placements stand for.
    std::size_t polygon_count() const {
        return placements.size() * std::size_t(cols) * std::size_t(rows);
    }
};

// Shapes and placements of `polygons`; with tiles_cols x tiles_rows > 1 and an active area that
// divides into whole-nanometre tiles, the placements of the bottom-left tile and the array when
// the other tiles are exact translations of it (checked; else no array).
Repetition find_repetition(const std::vector<Ring>& polygons, const BoxNm& active_area,
                           int tiles_rows, int tiles_cols);

// The polygons a repetition stands for: each tile, bottom-left first, row by row.
std::vector<Ring> expand(const Repetition& repetition);

}  // namespace pinmask
