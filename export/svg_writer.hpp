// SVG fabrication drawing of a layout, exactly 1:1: width and height in millimetres, the viewBox
// in micrometres (1 user unit = 1 um), so every coordinate is the layout's integer nanometres
// written with three decimals. SVG's y axis points down: y_svg = -y. Each ring is one
// <path d="Mx,yLx,y...Z"/> filled black; group "pattern" holds the tone polygons, group
// "annotations" the marks and label. The tone, mirroring, units and mask hash are written in a
// comment and in <metadata> (export/geometry layout_info). Deterministic: the same layout gives
// the same bytes.
#pragma once

#include <string>

#include "export/layout.hpp"

namespace pinmask {

// The complete SVG document.
std::string svg_document(const Layout& layout);

}  // namespace pinmask
