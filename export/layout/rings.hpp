// Small exact operations on rings (export/layout/layout.hpp: integer nanometres, counter-clockwise,
// last vertex not repeated) shared by the geometry builder, the writers and the readers.
// Areas are returned doubled (2A) so they stay integers: with |coordinates| <= 2^30 nm each
// cross product fits 64 bits and their sum is accumulated in 128 bits.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

__extension__ typedef __int128 WideInt;  // GCC/Clang 128-bit integer (exact doubled areas)

// Twice the signed area of a ring (positive for counter-clockwise), exact.
WideInt doubled_area(const Ring& ring);

// Bounding box of the vertices of every ring; an empty set gives an all-zero box.
BoxNm bounding_box(const std::vector<Ring>& rings);

// Smallest box containing both.
BoxNm box_union(const BoxNm& a, const BoxNm& b);

// The ring of an axis-aligned box, counter-clockwise from (x0, y0).
Ring box_ring(const BoxNm& box);

// Removes a repeated closing vertex, consecutive duplicates and collinear middle vertices
// (straight runs and 180-degree spikes), then orients the ring counter-clockwise. Returns an
// empty ring when fewer than 3 vertices remain (a degenerate ring has no area).
Ring simplified(Ring ring);

// Canonical form of a ring set for exact comparison: every ring simplified, rotated to start at
// its smallest (x, y) vertex, and the rings sorted. Two files describe the same polygons iff
// their canonical sets are equal. Degenerate rings are dropped.
std::vector<Ring> canonical_rings(std::vector<Ring> rings);

// x -> -x for every vertex, orientation restored to counter-clockwise.
Ring mirrored_about_y_axis(const Ring& ring);

// Bytes one ring of `vertices` vertices costs at the peak of `pinmask check`: the reader's copy,
// the check's split into pinholes and annotations and the design-rule check's working copies.
// Measured 527 bytes a 4-vertex ring (3.3 million rectangles of an OASIS repetition peaked at
// 1.74 GB), 4.4 times the ring's own 120 bytes; charged at 5 times. The readers whose files
// expand (OASIS repetitions, GDSII references) charge it per ring made, so a file that expands
// beyond the memory budget is refused in the reader, before the check would exceed the budget.
inline double ring_check_bytes(std::size_t vertices) {
    return 5.0 * (16.0 * double(vertices) + 56.0);
}

// Geometry read back from a fabrication file: its rings in nanometres (in file order, closing
// vertex removed) and the metadata it declares (keys such as "hash", "tone", "mirrored",
// "units"; values as written).
struct FileGeometry {
    std::vector<Ring> rings;
    std::vector<CircleNm> circles;  // native circles (DXF CIRCLE, Gerber circular flashes)
    std::map<std::string, std::string> info;
    // What identifies the film in the file: the layers its geometry is drawn on, distinct, in
    // first-use order (GDSII and OASIS "layer/datatype", DXF layer names); empty for formats
    // without layers (Gerber, SVG).
    std::vector<std::string> layers;
};

}  // namespace pinmask
