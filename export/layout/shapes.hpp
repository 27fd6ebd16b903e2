// Pinhole shapes on the manufacturing grid. Lengths in nanometres: exact positions as double,
// snapped vertices as integers (export/layout/layout.hpp). A circle of radius r is drawn as the
// inscribed regular N-gon whose sagitta r (1 - cos(pi / N)) is at most the chord tolerance;
// its vertices sit at angles (2k + 1) pi / N, so for N a multiple of 4 the polygon has flat
// sides facing the cell edges and no vertex on the cell's axes.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

// Most sides a pinhole polygon may have: it must fit one GDSII XY record (8190 vertices).
inline constexpr int kMaxPolygonSides = 8000;

// Nearest multiple of grid_nm (ties away from zero). grid_nm >= 1.
std::int64_t snap_nm(double v_nm, std::int64_t grid_nm);

// Largest multiple of grid_nm <= v_nm, and smallest >= v_nm.
std::int64_t floor_to_grid(double v_nm, std::int64_t grid_nm);
std::int64_t ceil_to_grid(double v_nm, std::int64_t grid_nm);

// "12.5 nm": a length for messages (6 significant digits).
std::string nm_text(double nm);

// Sagitta (greatest distance between a chord and its arc) of a regular N-gon inscribed in a
// circle of radius r: r (1 - cos(pi / N)), in nm.
double sagitta_nm(double radius_nm, int sides);

// Smallest N, a multiple of 4 and >= 8, with sagitta_nm(r, N) <= tolerance. Throws InvalidInput
// naming `chord_tolerance` when that needs more than kMaxPolygonSides sides or the inputs are
// not positive and finite.
int sides_for_chord_tolerance(double radius_nm, double tolerance_nm);

// Sides of the polygon that stands for a circle of radius r, at most max_vertices (the vertex
// limit the design-rule check applies to every polygon). tolerance_nm > 0: the fewest sides
// within it (sides_for_chord_tolerance); InvalidInput naming `chord_tolerance` when that exceeds
// max_vertices, with the finest tolerance that fits. tolerance_nm == 0 (auto): the most sides, a
// multiple of 4, within max_vertices, but none beyond a sagitta of one grid step (finer would be
// undone by snapping to the grid). Always >= 8.
int circle_sides(double radius_nm, double tolerance_nm, std::size_t max_vertices,
                 std::int64_t grid_nm);

// The regular N-gon inscribed in the circle (centre cx, cy; radius r; all nm) with vertices at
// angles (2k + 1) pi / N, each coordinate snapped to the grid towards the centre and clamped to
// at least one grid step inside `cell`, so polygons of different cells never touch. Collinear
// snapped vertices are dropped. Throws InvalidInput if the snapped polygon is not strictly
// convex (the grid is too coarse for the radius) or sides < 3.
Ring regular_polygon(double cx_nm, double cy_nm, double radius_nm, int sides, const BoxNm& cell,
                     std::int64_t grid_nm);

// The unsnapped vertex offsets (r cos a_k, r sin a_k), a_k = (2k + 1) pi / N, of
// regular_polygon: computed once and placed at many centres.
std::vector<std::pair<double, double>> regular_polygon_offsets(double radius_nm, int sides);

// regular_polygon from precomputed offsets (same snapping, clamping and convexity check).
Ring place_polygon(const std::vector<std::pair<double, double>>& offsets, double cx_nm,
                   double cy_nm, const BoxNm& cell, std::int64_t grid_nm);

// True iff every turn of the ring is a strict left turn (a strictly convex counter-clockwise
// polygon with >= 3 vertices).
bool is_strictly_convex_ccw(const Ring& ring);

}  // namespace pinmask
