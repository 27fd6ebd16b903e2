// Reads back the SVG drawings pinmask writes (export/formats/svg_writer): every <path> (absolute M,
// L, H, V, Z commands; each subpath closed with Z) and <polygon points> becomes a ring in integer
// nanometres (viewBox units are micrometres, y_svg = -y); <metadata> gives the info tokens.
// Strict and bounded: anything else in path data, an unclosed subpath, a coordinate off the 1 nm
// grid, or a document without its closing </svg> throws InvalidInput; memory stays proportional
// to the input. Constructs that would change the geometry and are not implemented are refused by
// name, never ignored: any element but svg, g, path, polygon, metadata, title, desc (so <use>,
// <rect>, <circle>, <ellipse>, <line>, <polyline>, <text>, <image>, <defs>, <clipPath>...), a
// nested <svg>, any attribute but the writer's (d, points, fill, stroke="none", id; on the root
// xmlns, version, width, height, viewBox: so transform, style, class, display, visibility,
// opacity, fill-opacity, clip-path, stroke-width... are refused), a fill that is not black (or
// white where a film drawing's clear rings are), single-quoted attributes, a DOCTYPE or other
// markup declaration (it can default attributes) and processing instructions other than the XML
// declaration (stylesheets), and a viewBox whose scale is not 1 user unit = 1 um (width and
// height, when given, must equal the viewBox size in micrometres; without them the user unit is
// taken as 1 um, pinmask's convention). Both draw modes are read: a film drawing's plate group
// (export/formats/svg_writer kSvgFilmGroup) must be one rectangle equal to the viewBox and is not
// returned; the rings on it (white) are the drawn rings, as the black ones of a polygons drawing.
#pragma once

#include <string_view>

#include "export/layout/rings.hpp"

namespace pinmask {

FileGeometry read_svg(std::string_view text);

}  // namespace pinmask
