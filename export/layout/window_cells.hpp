// A dictionary of window patterns for hierarchical GDSII (export/formats/gds_writer): the
// placements of one tile (export/layout/repetition) are cut by a grid of windows w x h lattice
// pitches; each distinct window content (the shapes and their offsets from the window's corner)
// becomes one cell, and the tile references a cell once per non-empty window. On a pattern with few
// distinct windows (a jittered lattice: one pinhole per 3 x 3 block at one of 4 places) a
// reference then stands for several pinholes, so the file shrinks well below one reference per
// pinhole; on a uniformly random pattern nearly every window is distinct and the gain is small.
// Exact: expand_windows gives back the same placements.
// The window is chosen by the exact byte count of the GDSII it gives (a reference of
// ref_bytes per use and per cell entry, cell_bytes per cell) over a fixed candidate list, the
// first smallest wins (deterministic); no windows (one reference per pinhole) when that is
// smallest or the placements are not on a lattice.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "export/layout/repetition.hpp"

namespace pinmask {

struct WindowCells {
    int w = 0, h = 0;                             // window in lattice pitches (0: none)
    std::int64_t pitch_x_nm = 0, pitch_y_nm = 0;  // the lattice (gcd of the offsets)
    std::vector<std::vector<Placement>> cells;    // distinct contents, relative offsets
    std::vector<Placement> uses;                  // shape = cell index, at = window corner
    std::size_t bytes = 0;                        // the cost model's count for the choice
};

struct WindowCost {
    std::size_t ref_bytes = 32;   // one SREF element
    std::size_t cell_bytes = 44;  // BGNSTR + STRNAME + ENDSTR of one cell
};

// The cheapest windowing of `placements` (w = 0 when none beats one reference each).
WindowCells find_window_cells(const std::vector<Placement>& placements, const WindowCost& cost);

// The placements the windows stand for (each window's cell contents moved to its corner).
std::vector<Placement> expand_windows(const WindowCells& windows);

}  // namespace pinmask
