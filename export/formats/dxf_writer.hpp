// DXF R12 (AC1009) drawing of a layout, coordinates in the chosen unit (um: 3 decimals, mm: 6,
// both the layout's integer nanometres exactly; in: 9 decimals, 0.0254 nm, which reads back to
// the same nanometre). The unit is written three ways: $INSUNITS (13 um, 4 mm, 1 in; R12 readers
// ignore it, newer ones and ezdxf honour it), $MEASUREMENT (1 metric, 0 inch) and a 999 comment
// at the top (with the tone, mirroring and mask hash, export/layout/geometry layout_info).
// Sections: HEADER ($ACADVER, $MEASUREMENT, $EXTMIN, $EXTMAX), TABLES (LTYPE CONTINUOUS and one
// named LAYER), ENTITIES with each ring as a closed POLYLINE (66 = 1, 70 = 1) with one VERTEX per
// corner and SEQEND. No handles
// ($HANDLING 0). Deterministic: the same layout gives the same bytes.
#pragma once

#include <string>

#include "export/formats/fab_units.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

struct DxfOptions {
    // Layer of every entity: 1..31 characters of A-Z a-z 0-9 _ - $, not "0".
    std::string layer = "PINMASK";
    FabUnit unit = FabUnit::kMicrometre;  // one drawing unit
    // Round pinholes (layout.circles non-empty) as CIRCLE entities (centre 10/20, radius 40)
    // instead of their polygons; layouts without circles are unaffected.
    bool native_circles = false;
};

std::string dxf_document(const Layout& layout, const DxfOptions& options = {});

}  // namespace pinmask
