// GDSII stream (release 6.0.0) of a layout: one library "PINMASK" with one top structure
// "PINMASK_<hash>", UNITS of 1 nm per database unit (coordinates are the layout's integers) and
// the user unit of GdsOptions (default 1 um: 1e-3 user units per database unit). Each ring is a
// BOUNDARY on the given layer/datatype with its first point repeated at the end (<= 8191
// points per XY record). One TEXT element on the same layer and texttype 0 carries the info
// tokens (export/layout/geometry layout_info). BGNLIB/BGNSTR timestamps are pinned to 2000-01-01
// 00:00:00 so the stream is byte-identical for identical layouts.
#pragma once

#include <cstdint>
#include <string>

#include "export/formats/fab_units.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

struct GdsOptions {
    int layer = 1;     // 0..32767
    int datatype = 0;  // 0..32767
    // The user unit (UNITS' first real: user units per database unit, 1e-3 for um, 1e-6 for mm,
    // 1e-9 / 0.0254 for inches); the database unit stays 1 nm, so coordinates do not change.
    FabUnit unit = FabUnit::kMicrometre;
    // Hierarchy: each distinct pinhole polygon becomes a structure "P<hhhh>S<k>" (hhhh: the
    // first 4 hex digits of the mask hash; short, because every reference repeats the name)
    // holding it at the origin; each distinct window of one tile's pinholes (export/
    // window_cells, when that makes the file smaller) a structure "P<hhhh>W<k>" referencing the
    // shapes; a structure "PINMASK_<hash>_TILE" references the windows (or the shapes, one SREF
    // per pinhole) for one tile, and the top structure places the tile as an array (AREF, tile
    // columns x rows at the tile pitch) when the pinholes repeat exactly across tiles
    // (export/layout/repetition), else once. Marks, label and text stay in the top structure.
    // Flattened, the same polygons as the flat stream.
    bool hierarchy = false;
};

// The complete stream. Throws InvalidInput for layer/datatype out of range, a ring of more than
// 8190 vertices or a coordinate outside the 32-bit range.
std::string gds_stream(const Layout& layout, const GdsOptions& options = {});

// GDSII 8-byte real: sign bit, 7-bit excess-64 base-16 exponent, 56-bit mantissa m with
// value = (-1)^s * m / 2^56 * 16^(e - 64), normalised so 1/16 <= m / 2^56 < 1 (0 is all zero).
// Big-endian bit layout in the returned integer. Rounds to nearest; |value| must be below
// 16^63 and finite (InvalidInput otherwise); values below 16^-65 become 0.
std::uint64_t gds_real8_bits(double value);
double gds_real8_value(std::uint64_t bits);

}  // namespace pinmask
