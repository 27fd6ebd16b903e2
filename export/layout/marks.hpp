// Marks outside the active area, as polygons in integer nanometres (y up): alignment crosses and
// text labels in a built-in 5 x 7 dot-matrix font whose pixels in one row are merged into
// horizontal bars. Every bar is shrunk by a gap on its right and bottom sides, so bars of one
// glyph, of neighbouring glyphs and of neighbouring lines never touch or overlap.
// Character cell: 6 x 9 pixels (5 x 7 glyph, one column and two rows of spacing).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

// A cross centred at `centre`: two bars of length 2 * arm and width 2 * half_width, as one
// 12-vertex counter-clockwise polygon. arm > half_width > 0.
Ring cross_ring(PointNm centre, std::int64_t arm_nm, std::int64_t half_width_nm);

// Four crosses beyond the corners of `outline`, each `gap` clear of the outline in x and y.
std::vector<Ring> corner_crosses(const BoxNm& outline, std::int64_t arm_nm,
                                 std::int64_t half_width_nm, std::int64_t gap_nm);

// True for the characters of the font: 0-9, A-Z, space and - . : _ / = + ,
bool has_glyph(char c);

// Upper-cases letters and replaces characters without a glyph by '-'.
std::string label_text(std::string_view text);

// Bars of the text lines, the first line's top-left corner at `top_left`, lines going down.
// pixel_nm > gap_nm > 0. Characters without a glyph throw InvalidInput (use label_text).
std::vector<Ring> text_rings(const std::vector<std::string>& lines, PointNm top_left,
                             std::int64_t pixel_nm, std::int64_t gap_nm);

// The box text_rings may cover: 6 pixels per character minus the trailing column, 9 pixels per
// line minus the trailing two rows.
BoxNm text_box(const std::vector<std::string>& lines, PointNm top_left, std::int64_t pixel_nm);

}  // namespace pinmask
