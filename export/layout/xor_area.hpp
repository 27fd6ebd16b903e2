// Exact Boolean operations and areas of polygon sets (rings in integer nanometres,
// export/layout/layout.hpp), for golden comparisons of exported files against their design and for
// the design-rule check. The Boolean operations run in CGAL with an exact kernel (Epeck); only the
// final area is rounded to double (relative error <= 2^-53). Areas in nm^2.
//
// Rings whose bounding boxes touch or overlap are grouped (CGAL box sweep) and each group is
// evaluated on its own: one ring, two equal rings or two rectangles in 128-bit integers, other
// groups with CGAL polygon sets. 100k identical or shifted squares take under a second; groups
// that need CGAL cost about half a millisecond each.
//
// Input rings must be simple (no self-intersection) with at least 3 vertices and coordinates
// within +-kMaxCoordNm; either orientation is accepted (clockwise rings are reversed). Rings of
// one set may overlap or touch: each set is the union of its rings.
#pragma once

#include <cstdint>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

// Largest |coordinate| the exact geometry code accepts: 2^30 nm (about 1.07 m), which keeps
// every squared distance and cross product of the design-rule check inside 128-bit integers.
inline constexpr std::int64_t kMaxCoordNm = std::int64_t{1} << 30;

// Area of the symmetric difference of union(a) and union(b), in nm^2. 0 iff the sets cover the
// same region (up to measure zero). Throws InvalidInput naming the set and ring of a bad ring.
double xor_area_nm2(const std::vector<Ring>& a, const std::vector<Ring>& b);

// Area of union(a) intersected with union(b), in nm^2 (regularised: touching boundaries give 0).
double intersection_area_nm2(const std::vector<Ring>& a, const std::vector<Ring>& b);

// Area of union(a), in nm^2.
double union_area_nm2(const std::vector<Ring>& a);

// The holes of union(opaque), as counter-clockwise rings: the clear pinholes of a dark-tone
// layout, whose opaque pieces share edges. Exact; throws InvalidInput when a hole has a vertex
// off the 1 nm grid (pieces that cross between grid points). A clear region open to the
// outside (a pinhole cut into the outline's edge) is not a hole and is not returned.
std::vector<Ring> union_holes(const std::vector<Ring>& opaque);

}  // namespace pinmask
