#include "report/plot_canvas.hpp"

#include <cairo-svg.h>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"

namespace pinmask {
namespace {

using Surface = cairo::SurfacePtr;
using Context = cairo::ContextPtr;

void check(cairo_t* cr, cairo_surface_t* s, const std::string& what,
           const std::filesystem::path& path) {
    cairo_surface_flush(s);
    const cairo_status_t st =
        cairo_status(cr) != CAIRO_STATUS_SUCCESS ? cairo_status(cr) : cairo_surface_status(s);
    if (st != CAIRO_STATUS_SUCCESS)
        throw RuntimeFailure(what + " " + path.string() + ": " + cairo_status_to_string(st));
}

}  // namespace

void write_plot_svg(const std::filesystem::path& path, int width, int height,
                    const std::string& what, const PlotDraw& draw) {
    Surface s(cairo_svg_surface_create(path.c_str(), width, height));
    Context cr(cairo_create(s.get()));
    draw(cr.get());
    check(cr.get(), s.get(), what, path);
    cr.reset();
    cairo_surface_finish(s.get());
    if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure(what + " " + path.string() + ": " +
                             cairo_status_to_string(cairo_surface_status(s.get())));
    }
}

void write_plot_png(const std::filesystem::path& path, int width, int height,
                    const std::string& what, const PlotDraw& draw) {
    Surface s(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height));
    Context cr(cairo_create(s.get()));
    draw(cr.get());
    check(cr.get(), s.get(), what, path);
    if (cairo_surface_write_to_png(s.get(), path.c_str()) != CAIRO_STATUS_SUCCESS)
        throw RuntimeFailure(what + " " + path.string() + ": PNG write failed");
}

void plot_label(cairo_t* cr, double x, double y, const std::string& s, double size, double align) {
    cairo_set_font_size(cr, size);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    cairo_move_to(cr, x - align * e.width, y);
    cairo_show_text(cr, s.c_str());
}

}  // namespace pinmask
