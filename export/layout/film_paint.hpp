// Paints a layout as the physical film looks (black = opaque, white = clear) into a Cairo
// context, shared by the PDF writer and the PNG preview. The caller sets the context's matrix so
// user space is the layout's nanometres with y up.
//   clear tone: the extent is filled black (the plate is opaque wherever nothing is drawn), then
//               every polygon and annotation is filled white;
//   dark tone:  every polygon and annotation is filled black (the rest stays clear).
// All rings go into one path and one fill, which keeps Cairo fast for 10^5 polygons.
#pragma once

#include <cairo.h>

#include <string>
#include <string_view>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

// What a picture shows: the final film (above) or the drawn polygons black on white, whatever
// the tone (so a clear-tone layout gives a drawing of opaque pinholes).
enum class DrawMode { kFilm, kPolygons };

// "film" or "polygons"; anything else throws InvalidInput naming `field`.
DrawMode parse_draw_mode(std::string_view text, std::string_view field);
std::string draw_mode_name(DrawMode mode);

// One fill of a picture: rings in one path, filled (non-zero winding) in one colour.
struct FilmFill {
    bool white = false;  // else black
    std::vector<Ring> rings;
};

// What paint_film paints, in order: clear tone in film mode: the extent black, then every
// polygon and annotation white; otherwise every polygon and annotation black.
std::vector<FilmFill> film_fills(const Layout& layout, DrawMode mode = DrawMode::kFilm);

void paint_film(cairo_t* cr, const Layout& layout, DrawMode mode = DrawMode::kFilm);

// Fills the rings black (or white) (nanometre user space), one path.
void fill_rings(cairo_t* cr, const std::vector<Ring>& rings, bool white = false);

// Throws RuntimeFailure naming `what` when the surface or context is in an error state.
void check_cairo(cairo_t* cr, const std::string& what);
void check_cairo_surface(cairo_surface_t* surface, const std::string& what);

}  // namespace pinmask
