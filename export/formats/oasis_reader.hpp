// Reads back OASIS files like the ones pinmask writes (export/formats/oasis_writer): one cell of
// RECTANGLE and POLYGON records (point-list types 0..4), with repetitions of type 0..11
// expanded, TEXT records (the info tokens), XYABSOLUTE/XYRELATIVE, PAD, and CELLNAME/TEXTSTRING
// name records (skipped: pinmask reads inline names only). Every other construct is refused
// (InvalidInput naming the record): PLACEMENT (hierarchy), PATH, TRAPEZOID, CTRAPEZOID, CIRCLE,
// PROPERTY, XNAME, XELEMENT, XGEOMETRY, CBLOCK (compression), LAYERNAME, PROPNAME, PROPSTRING,
// a second cell, name references, and table offsets in the END record. The database unit must be
// a whole number of nanometres. Bounded: the rings a repetition expands to are charged to the
// memory budget before they are made.
#pragma once

#include <string_view>

#include "export/layout/rings.hpp"

namespace pinmask {

FileGeometry read_oasis(std::string_view bytes);

}  // namespace pinmask
