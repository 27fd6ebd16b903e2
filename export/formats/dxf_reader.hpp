// Reads back DXF drawings like the ones pinmask writes (export/formats/dxf_writer): closed POLYLINE
// (with VERTEX ... SEQEND) and LWPOLYLINE entities in the ENTITIES section become rings, with
// coordinates converted exactly to integer nanometres; 999 comments give the info tokens.
// Units: the header's $INSUNITS (1 in, 4 mm, 5 cm, 6 m, 9 mil, 12 nm, 13 um, 14 dm; any other
// non-zero code is refused), else pinmask's own "units=" comment, else (0 or absent: the file
// states no unit) micrometres, pinmask's historical DXF unit; the two statements must agree.
// info["unit_nm"] is the unit used. Strict and bounded: a missing EOF marker (truncation), an open
// polyline, a bulge (arc segment), any other entity, malformed group codes or off-grid coordinates
// throw InvalidInput naming the line. Memory stays proportional to the input.
#pragma once

#include <string_view>

#include "export/layout/rings.hpp"

namespace pinmask {

FileGeometry read_dxf(std::string_view text);

}  // namespace pinmask
