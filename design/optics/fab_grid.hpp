// The fabrication grid (docs/design.md section 2, "Fabrication grid"): every coordinate a shop
// receives is a whole number of grid steps (1 nm unless the vendor says otherwise). The pinhole
// side d is the cell pitch of the mask; it is snapped to the grid once, here, and everything
// that lays out or measures the mask (design's solved pinhole, generate's spacing report,
// layout's cell edges, the design-rule check's spacing limit) uses that one integer pitch P.
// Cells then sit exactly P apart, so two pinholes k cells apart are exactly sqrt(k) P apart and
// the spacing rule reads the same in cells (generate) and in nanometres (export, check).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "design/pattern/pattern.hpp"

namespace pinmask {

inline constexpr std::int64_t kDefaultFabGridNm = 1;
// The largest pitch on a grid: 2^30 nm (about 1.07 m), the coordinate bound of the layouts.
inline constexpr double kMaxGridPitchM = 1073741824e-9;
// Pinhole centres are computed in double from integer vertices; at |coordinate| <= 2^30 nm their
// error is below 1e-6 nm, so a pair counts as too close only when short by more than this (the
// design-rule check and spacing_on_grid use the same tolerance).
inline constexpr double kCentroidToleranceNm = 1e-3;

// The grid in whole nanometres from metres; InvalidInput naming `field` unless it is a whole
// number of nm between 1 nm and 1 mm.
std::int64_t fab_grid_nm(double grid_m, const std::string& field);

// The pitch P in nm: d rounded to the nearest whole number of grid steps (at least one step).
// InvalidInput naming `pinhole_m` for a side that is not finite and > 0 or above 2^30 nm.
std::int64_t pitch_on_grid_nm(double pinhole_m, std::int64_t grid_nm);

// d snapped to the grid, in metres (P * 1e-9).
double pinhole_on_grid_m(double pinhole_m, std::int64_t grid_nm);

// The spacing rule of a pattern measured on the grid pitch: centres k cells apart (on the torus)
// are sqrt(k) P nm apart; a pair is too close when that is below min_spacing_cells * P by more
// than kCentroidToleranceNm.
struct GridSpacing {
    std::int64_t grid_nm = 1;
    std::int64_t pitch_nm = 0;
    double limit_nm = 0;            // min_spacing_cells * P
    double closest_nm = 0;          // closest pair's distance (inf: no pair within reach)
    std::size_t violations = 0;     // pairs too close
    Cell closest_a{}, closest_b{};  // the closest pair (when closest_nm is finite)
    bool ok() const { return violations == 0; }
};

GridSpacing spacing_on_grid(const Pattern& pattern, double pinhole_m, std::int64_t grid_nm);

// "centres 910.811 um apart < 910.812 um (2 x pitch 455.406 um on the 1 nm grid)": the
// words every command uses for a spacing violation on the grid.
std::string spacing_rule_text(double min_spacing_cells, std::int64_t pitch_nm,
                              std::int64_t grid_nm);

// A length in nm as micrometres with three decimals ("910.812 um"), as the check reports them.
std::string um_text(double nm);

}  // namespace pinmask
