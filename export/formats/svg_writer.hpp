// SVG fabrication drawing of a layout, exactly 1:1: width and height in millimetres, the viewBox
// in micrometres (1 user unit = 1 um), so every coordinate is the layout's integer nanometres
// written with three decimals. SVG's y axis points down: y_svg = -y. Each ring is one
// <path d="Mx,yLx,y...Z"/>; group "pattern" holds the tone polygons, group "annotations" the
// marks and label. Draw mode (export/layout/film_paint):
//   polygons: the drawn rings filled black on nothing (white paper), whatever the tone;
//   film:     the film as it looks. Dark tone: the same as polygons. Clear tone: first a group
//             kSvgFilmGroup holding one black rectangle, the extent (the opaque plate), then the
//             drawn rings filled white on it (the clear pinholes, marks and label).
// The metadata says draw=film|polygons; export/formats/svg_reader reads both (the film rectangle is
// not a drawn ring: it must be the extent, and is left out of the geometry). The tone, mirroring,
// units and mask hash are written in a comment and in <metadata> (export/layout/geometry
// layout_info). Deterministic: the same layout gives the same bytes.
#pragma once

#include <string>

#include "export/layout/film_paint.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

// id of the group that holds the opaque plate of a film drawing.
inline constexpr const char* kSvgFilmGroup = "film-plate";

// The complete SVG document (the default draws the polygons, as fabrication SVGs do).
std::string svg_document(const Layout& layout, DrawMode draw = DrawMode::kPolygons);

}  // namespace pinmask
