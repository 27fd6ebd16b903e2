// Mask geometry for fabrication, in integer nanometres on the manufacturing grid (database unit
// 1 nm), origin at the mask centre, y upwards (as in GDSII/DXF/Gerber; SVG/PDF writers flip).
// Exact integer coordinates make the design-rule check and the round-trip comparison exact.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pinmask {

struct PointNm {
    std::int64_t x = 0;
    std::int64_t y = 0;
    bool operator==(const PointNm&) const = default;
};

// A simple closed polygon: the last vertex connects back to the first (not repeated).
// Orientation: counter-clockwise.
using Ring = std::vector<PointNm>;

struct BoxNm {
    std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // x0 <= x1, y0 <= y1
};

// A true circle (a round pinhole drawn natively: DXF CIRCLE, Gerber circular flash), centre on
// the grid, diameter in whole nanometres.
struct CircleNm {
    PointNm centre;
    std::int64_t diameter_nm = 0;
    bool operator==(const CircleNm&) const = default;
    bool operator<(const CircleNm& o) const {
        if (centre.x != o.centre.x) return centre.x < o.centre.x;
        if (centre.y != o.centre.y) return centre.y < o.centre.y;
        return diameter_nm < o.diameter_nm;
    }
};

enum class Tone { kClear, kDark };  // clear: polygons are the transparent pinholes

// The polygons of one exported mask and what they mean.
struct Layout {
    std::vector<Ring> polygons;     // the drawn (tone) polygons, pinholes or opaque pieces
    std::vector<Ring> annotations;  // marks and label polygons, outside the active area
    BoxNm active_area;              // the tiled pattern's extent
    BoxNm extent;                   // everything incl. frame, marks and label
    Tone tone = Tone::kClear;
    bool mirrored = false;      // right-reading with chrome/emulsion down
    std::int64_t grid_nm = 1;   // manufacturing grid the coordinates are snapped to
    std::int64_t pitch_nm = 0;  // cell pitch: the pinhole side on the grid (design/optics/fab_grid)
    std::string mask_hash;      // geometry_hash of the source mask
    int hole_sides = 4;         // sides of each pinhole's polygon before snapping (4: squares)
    // Round pinholes in clear tone: the true circle each polygon stands for, in the same order
    // as `polygons` (writers with native circles draw these instead); empty otherwise.
    std::vector<CircleNm> circles;
    int tiles_rows = 1, tiles_cols = 1;  // the mask's cyclic tiling (export/layout/repetition)
};

}  // namespace pinmask
