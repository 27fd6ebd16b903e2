// Which design pinhole made which spot, once the lattice is registered (calibrate/registration).
// Mask cells are counted over the whole tiled mask: row R in 0 .. n * tiles_rows - 1, column C in
// 0 .. n * tiles_cols - 1; cell (R, C) is open when pattern cell (R mod n, C mod n) is. Lattice
// index (i, j) of the fit is mask cell (R, C) = (j + offset_row, i + offset_col); the offset is
// the one that puts the most spots on open cells, fewest on closed cells or off the mask, and
// leaves the fewest open cells inside the frame without a spot.
// A design pinhole is "in frame" when its predicted spot centre lies at least half a pitch plus
// one pixel inside the frame (a spot cut by the edge has a biased centroid and flux); only those
// are classified:
//   found      a spot sits on its lattice site;
//   merged     no spot on its site, but one spot's bounding box holds its predicted centre and
//              another open cell's (two spots ran together);
//   missing    neither: the pinhole did not open (or is blocked).
// A spot in frame that is neither on an open site nor merged is an extra spot (a pinhole not in
// the design, a scratch, dust in reverse). Spots outside the in-frame area are ignored.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "calibrate/registration.hpp"
#include "calibrate/spots.hpp"
#include "design/pattern.hpp"

namespace pinmask::calibrate {

enum class PinholeState { kFound, kMerged, kMissing };

struct PinholeRecord {
    Cell mask_cell;             // (R, C) over the tiled mask
    Eigen::Vector2d predicted;  // lattice position (x, y)
    Eigen::Vector2d measured;   // spot centroid (found only; else = predicted)
    PinholeState state = PinholeState::kMissing;
    int spot = -1;           // index into the spot list (found and merged)
    double gain = 0.0;       // flux / median flux of the found spots (found only)
    bool oversized = false;  // found, area > kOversizedArea x median area
};

struct PinholeMatch {
    int offset_row = 0, offset_col = 0;
    std::vector<PinholeRecord> pinholes;  // in-frame design pinholes, by (R, C)
    std::vector<int> extra_spots;         // indices into the spot list
    double median_flux = 0.0, median_area_px = 0.0;
};

inline constexpr double kOversizedArea = 1.8;

PinholeMatch match_pinholes(const std::vector<Spot>& spots, const LatticeFit& fit,
                            const Pattern& pattern, int frame_rows, int frame_cols,
                            double max_index_offset);

}  // namespace pinmask::calibrate
