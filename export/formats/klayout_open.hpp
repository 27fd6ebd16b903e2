// How to open an exported file at scale in KLayout, the free layout viewer shops and users
// check masks with, stated beside every export (its notes and sidecar). GDSII and OASIS carry
// their database unit and open at scale. KLayout's DXF reader ignores $INSUNITS and reads
// drawing units as its "DXF unit" option (micrometres unless set), so a DXF in millimetres
// opens 1000x too small unless the import is told the unit. Gerber is imported (File > Import)
// with its MO unit. SVG, PDF and the rasters are not layout files for KLayout.
#pragma once

#include <string>

#include "export/formats/fab_units.hpp"
#include "export/formats/read_any.hpp"

namespace pinmask {

// The DXF unit option KLayout needs for a DXF drawn in `unit`: micrometres per drawing unit
// (1, 1000, 25400).
double klayout_dxf_unit_um(FabUnit unit);

// One sentence: the file's drawing unit and how KLayout opens it at scale.
std::string klayout_open_text(FabFormat format, FabUnit unit);

}  // namespace pinmask
