// Reads back the SVG drawings pinmask writes (export/svg_writer): every <path> (absolute M, L,
// H, V, Z commands; each subpath closed with Z) and <polygon points> becomes a ring in integer
// nanometres (viewBox units are micrometres, y_svg = -y); <metadata> gives the info tokens.
// Strict and bounded: anything else in path data, an unclosed subpath, a coordinate off the 1 nm
// grid, or a document without its closing </svg> throws InvalidInput; memory stays proportional
// to the input.
#pragma once

#include <string_view>

#include "export/rings.hpp"

namespace pinmask {

FileGeometry read_svg(std::string_view text);

}  // namespace pinmask
