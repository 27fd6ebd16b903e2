#include "export/layout/film_paint.hpp"

#include "core/errors/error.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {
namespace {

void add_rings(cairo_t* cr, const std::vector<Ring>& rings) {
    for (const Ring& r : rings) {
        if (r.empty()) continue;
        cairo_move_to(cr, double(r[0].x), double(r[0].y));
        for (std::size_t i = 1; i < r.size(); ++i)
            cairo_line_to(cr, double(r[i].x), double(r[i].y));
        cairo_close_path(cr);
    }
}

}  // namespace

void fill_rings(cairo_t* cr, const std::vector<Ring>& rings, bool white) {
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
    const double c = white ? 1 : 0;
    cairo_set_source_rgb(cr, c, c, c);
    add_rings(cr, rings);
    cairo_fill(cr);
}

std::vector<FilmFill> film_fills(const Layout& layout, DrawMode mode) {
    const bool clear = layout.tone == Tone::kClear && mode == DrawMode::kFilm;
    std::vector<FilmFill> out;
    if (clear) out.push_back({false, {box_ring(layout.extent)}});
    FilmFill drawn{clear, layout.polygons};
    drawn.rings.insert(drawn.rings.end(), layout.annotations.begin(), layout.annotations.end());
    out.push_back(std::move(drawn));
    return out;
}

DrawMode parse_draw_mode(std::string_view text, std::string_view field) {
    if (text == "film") return DrawMode::kFilm;
    if (text == "polygons") return DrawMode::kPolygons;
    throw invalid_field(std::string(field), std::string(text),
                        "must be film (the film as it looks) or polygons (the drawn polygons "
                        "black on white)");
}

std::string draw_mode_name(DrawMode mode) { return mode == DrawMode::kFilm ? "film" : "polygons"; }

void paint_film(cairo_t* cr, const Layout& layout, DrawMode mode) {
    for (const FilmFill& f : film_fills(layout, mode)) fill_rings(cr, f.rings, f.white);
}

void check_cairo(cairo_t* cr, const std::string& what) {
    const cairo_status_t s = cairo_status(cr);
    if (s != CAIRO_STATUS_SUCCESS)
        throw RuntimeFailure(what + ": cairo: " + cairo_status_to_string(s));
}

void check_cairo_surface(cairo_surface_t* surface, const std::string& what) {
    const cairo_status_t s = cairo_surface_status(surface);
    if (s != CAIRO_STATUS_SUCCESS)
        throw RuntimeFailure(what + ": cairo: " + cairo_status_to_string(s));
}

}  // namespace pinmask
