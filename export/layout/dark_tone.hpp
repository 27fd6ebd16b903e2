// Dark tone: the drawn polygons are the opaque area (the outline minus the pinholes), split into
// simple hole-free pieces of at most max_vertices vertices, exactly on the grid (every piece
// vertex is a vertex of the outline, of a hole or of a cell box; no new intersection points).
//   Rectangular holes (square pinholes, touching or overlapping allowed): horizontal bands
//   between consecutive hole edges; in each band the outline width minus the holes gives runs,
//   and runs repeated in consecutive bands are merged into one rectangle.
//   Convex holes (circles, polygons): the hole's cell box is removed like a rectangular hole and
//   refilled by box_minus_convex: the part of the box above the hole's upper chain, the part
//   below its lower chain, and the rectangles beside vertical end edges. A part with too many
//   vertices is cut by vertical lines from chain vertices to the box edge (they stay outside
//   the convex hole, so every piece stays simple).
#pragma once

#include <cstddef>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

// A strictly convex counter-clockwise polygon strictly inside its cell box.
struct ConvexHole {
    BoxNm cell;
    Ring polygon;
};

// Pieces covering box minus the convex polygon `hole` (strictly inside the box), each simple,
// counter-clockwise, hole-free, with at most max_vertices (>= 8) vertices.
std::vector<Ring> box_minus_convex(const BoxNm& box, const Ring& hole, std::size_t max_vertices);

// The opaque pieces of outline minus every rectangle in `holes` and every convex hole (cell boxes
// of convex holes must not overlap each other or the rectangles). Rectangles are clipped to
// the outline. max_vertices >= 8.
std::vector<Ring> dark_pieces(const BoxNm& outline, const std::vector<BoxNm>& holes,
                              const std::vector<ConvexHole>& convex_holes,
                              std::size_t max_vertices);

}  // namespace pinmask
