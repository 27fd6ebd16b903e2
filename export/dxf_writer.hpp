// DXF R12 (AC1009) drawing of a layout, coordinates in micrometres (three decimals: the
// layout's integer nanometres exactly). R12 has no $INSUNITS header variable, so the units are
// stated in a 999 comment at the top (with the tone, mirroring and mask hash, export/geometry
// layout_info) and $MEASUREMENT is 1 (metric). Sections: HEADER ($ACADVER, $MEASUREMENT,
// $EXTMIN, $EXTMAX), TABLES (LTYPE CONTINUOUS and one named LAYER), ENTITIES with each ring as
// a closed POLYLINE (66 = 1, 70 = 1) with one VERTEX per corner and SEQEND. No handles
// ($HANDLING 0). Deterministic: the same layout gives the same bytes.
#pragma once

#include <string>

#include "export/layout.hpp"

namespace pinmask {

struct DxfOptions {
    // Layer of every entity: 1..31 characters of A-Z a-z 0-9 _ - $, not "0".
    std::string layer = "PINMASK";
};

std::string dxf_document(const Layout& layout, const DxfOptions& options = {});

}  // namespace pinmask
