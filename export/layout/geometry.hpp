// Mask -> fabrication geometry (export/layout/layout.hpp): every pinhole of the tiled mask as a
// polygon in integer nanometres on the manufacturing grid, origin at the centre of the active area.
//
// Orientation: mask row 0 is the TOP row and column 0 the LEFT column, as in the pattern's
// row-major occupancy; with y up (GDSII/DXF/Gerber), row r spans y from H/2 - (r + 1) d to
// H/2 - r d and column c spans x from c d - W/2 to (c + 1) d - W/2, where d is the cell pitch
// (camera.pinhole_m) and W, H the tiled width and height. Row -> -y, column -> +x. The pitch is
// snapped to the grid once (design/optics/fab_grid pitch_on_grid_nm) and W/2, H/2 rounded down to
// it, so every cell edge is on the grid, neighbouring cells share their edge exactly, and every
// pinhole is the first one moved by whole pitches (the spacing rule sees exact multiples of P).
// Mirroring (right-reading with the chrome/emulsion side down) maps x -> -x for everything,
// marks and label included, after the layout is built.
//
// Shapes: squares of side hole_side (default: the full cell, so neighbouring pinholes share
// edges; only possible with the spacing rule off, e.g. MURA, and then merged exactly by
// export/layout/cell_union), circles as inscribed regular polygons with sagitta <= chord tolerance,
// or regular polygons of a given number of sides (export/layout/shapes). Circles and polygons keep
// at least one grid step inside their cell, so they never touch. Tone clear: the polygons are the
// pinholes. Tone dark: the polygons are the opaque area, outline (active area plus frame) minus
// the pinholes, split into hole-free pieces (export/layout/dark_tone).
// Annotations (always drawn in the tone's sense, outside the outline): four alignment crosses
// beyond the outline's corners and a text label below the outline (export/layout/marks).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "design/pattern/mask.hpp"
#include "export/layout/layout.hpp"
#include "export/layout/vendor_rules.hpp"

namespace pinmask {

enum class HoleShape { kSquare, kCircle, kPolygon };

struct LayoutOptions {
    HoleShape shape = HoleShape::kSquare;
    int polygon_sides = 8;     // kPolygon only, >= 3
    double hole_side_m = 0.0;  // square side or circle diameter; 0: the cell pitch
    // kCircle: greatest sagitta of the inscribed polygon (clear tone: refused when that needs
    // more than max_vertices); 0 (auto): the finest polygon within max_vertices
    // (export/layout/shapes circle_sides).
    double chord_tolerance_m = 0.0;
    double grid_m = 1e-9;  // manufacturing grid, a whole number of nanometres
    Tone tone = Tone::kClear;
    bool mirror = false;
    double frame_m = 0.0;  // opaque border added around the active area (the outline)
    bool marks = false;
    double mark_arm_m = 250e-6;            // half length of each cross bar
    double mark_width_m = 50e-6;           // width of each cross bar
    double mark_gap_m = 250e-6;            // clearance between the outline and marks / label
    std::vector<std::string> label_lines;  // empty: no label (see default_label_lines)
    // Font pixel; a character is 6 x 9 pixels and bars are half a pixel apart (40 um: bars and
    // gaps of 20 um, above the 16 um a film plotter needs).
    double label_pixel_m = 40e-6;
    // Largest vertex count of any polygon: pieces this code splits (cell unions, dark-tone
    // pieces) are split to it, and circles are drawn within it (a tolerance that needs more is
    // refused).
    std::size_t max_vertices = kGdsFriendlyMaxVertices;
};

// Builds the layout. Throws InvalidInput naming the option for a value out of range (grid not
// a whole number of nm, hole larger than the cell, a frame < 0, coordinates beyond
// +-kMaxCoordNm...) and for a mask without pinholes (the export would be empty).
Layout make_layout(const Mask& mask, const LayoutOptions& options);

// Label lines for a mask: "ID <id>", "H <geometry hash>", "SCALE 1:1 D <pitch in um>UM", in
// the font's character set (export/layout/marks label_text).
std::vector<std::string> default_label_lines(const Mask& mask, std::string_view id);

// Polygons then annotations: everything a fabrication file of the layout contains.
std::vector<Ring> all_rings(const Layout& layout);

// The metadata every fabrication file carries (comment, property or text element), as
// space-separated key=value tokens: "hash=<geometry hash> tone=<clear|dark>
// drawn=<clear|opaque> mirrored=<yes|no> units=<units> grid_nm=<grid>".
std::string layout_info(const Layout& layout, std::string_view units);

// The key=value tokens of a text (whitespace-separated; other words are ignored).
std::map<std::string, std::string> parse_info(std::string_view text);

// Parses "square", "circle" or "polygon"; anything else throws InvalidInput naming `field`.
HoleShape parse_hole_shape(std::string_view text, std::string_view field);
// "clear" or "dark", or the film shops' words: "negative" = clear (the drawn polygons are the
// clear areas, the plotter exposes everything else: a negative of the drawing) and "positive" =
// dark (the drawn polygons are the opaque film).
Tone parse_tone(std::string_view text, std::string_view field);
// The tone in words, e.g. "clear (negative): polygons are the clear pinholes".
std::string tone_words(Tone tone);
// The label line stating tone, emulsion side and unit in the label font's characters, e.g.
// "CLEAR HOLES NEG EMUL UP UNIT MM" (emulsion down = mirrored, right-reading through the base).
std::string tone_label_line(Tone tone, bool mirrored, std::string_view unit);
std::string tone_name(Tone tone);

}  // namespace pinmask
