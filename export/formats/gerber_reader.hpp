// Reads back Gerber files like the ones pinmask writes (export/formats/gerber_writer): every
// G36/G37 region contour (D02 start, D01 segments, closed at its start point) becomes a ring in
// integer nanometres. Needs %MOMM*% and %FSLA...*% (leading zeros omitted, absolute) with at most 6
// decimals before the first coordinate; G04 comments give the info tokens and
// %TF.FilePolarity% gives info "polarity". Strict and bounded: apertures, flashes, strokes
// outside regions, arcs, clear polarity, unclosed contours, a missing M02 (truncation) or
// anything unknown throw InvalidInput naming the byte offset. Memory stays proportional to the
// input.
#pragma once

#include <string_view>

#include "export/layout/rings.hpp"

namespace pinmask {

FileGeometry read_gerber(std::string_view text);

}  // namespace pinmask
