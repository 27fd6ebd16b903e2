// OASIS (SEMI P39) file of a layout: the compact successor of GDSII that mask shops prefer.
// One cell "PINMASK_<hash>", database unit 1 nm (START unit: 1000 grid steps per micron), one
// layer/datatype, coordinates relative to the previous element (XYRELATIVE). Axis-aligned boxes
// are RECTANGLE records (squares with the S bit), other rings POLYGON records with a general
// (g-delta) point list; width, height and point list are modal, so a repeated shape costs only
// its position. When the pinholes repeat exactly across the mask's tiles
// (export/layout/repetition), one tile is written and each record carries a grid repetition (type
// 1, 2 or 3) over the tile array. Marks and label follow as plain records; a TEXT record carries
// the info tokens (export/layout/geometry layout_info). No CBLOCK compression, no name tables (the
// cell and text strings are inline), no validation signature; the END record is padded to 256
// bytes. Deterministic: the same layout gives the same bytes.
#pragma once

#include <string>

#include "export/formats/fab_units.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

struct OasisOptions {
    int layer = 1;                        // >= 0
    int datatype = 0;                     // >= 0
    FabUnit unit = FabUnit::kMicrometre;  // stated in the info text (OASIS's own unit is 1 um)
    bool repetitions = true;              // use the tile array when the pinholes repeat
};

std::string oasis_file(const Layout& layout, const OasisOptions& options = {});

}  // namespace pinmask
