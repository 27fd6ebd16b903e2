// Reads back DXF drawings like the ones pinmask writes (export/dxf_writer): closed POLYLINE
// (with VERTEX ... SEQEND) and LWPOLYLINE entities in the ENTITIES section become rings, with
// coordinates in micrometres converted exactly to integer nanometres; 999 comments give the
// info tokens. Strict and bounded: a missing EOF marker (truncation), an open polyline, a
// bulge (arc segment), any other entity, malformed group codes or off-grid coordinates throw
// InvalidInput naming the line. Memory stays proportional to the input.
#pragma once

#include <string_view>

#include "export/rings.hpp"

namespace pinmask {

FileGeometry read_dxf(std::string_view text);

}  // namespace pinmask
