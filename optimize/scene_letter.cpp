// The letter-R scene: Cairo renders the outline of a bold sans-serif "R" into an 8-bit alpha
// surface; the ink box is stretched to the frame minus kLetterMargin on each side.
#include <cairo.h>

#include <memory>

#include "core/error.hpp"
#include "optimize/scenes.hpp"

namespace pinmask {
namespace {

struct SurfaceDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
    void operator()(cairo_t* c) const { cairo_destroy(c); }
};
struct OptionsDeleter {
    void operator()(cairo_font_options_t* o) const { cairo_font_options_destroy(o); }
};

constexpr double kReferenceFontSize = 100.0;  // user units; only the ratio to the ink box matters

}  // namespace

Plane letter_r_scene(int rows, int cols) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput("scene size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
    std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
        cairo_image_surface_create(CAIRO_FORMAT_A8, cols, rows));
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure("letter-R scene: Cairo could not create a " + std::to_string(cols) +
                             " x " + std::to_string(rows) + " surface");
    }
    std::unique_ptr<cairo_t, ContextDeleter> cr(cairo_create(surface.get()));
    std::unique_ptr<cairo_font_options_t, OptionsDeleter> options(cairo_font_options_create());
    // Unhinted outlines: the glyph shape does not snap to the pixel grid, so it scales smoothly.
    cairo_font_options_set_hint_style(options.get(), CAIRO_HINT_STYLE_NONE);
    cairo_font_options_set_hint_metrics(options.get(), CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_antialias(options.get(), CAIRO_ANTIALIAS_GRAY);
    cairo_set_font_options(cr.get(), options.get());
    cairo_select_font_face(cr.get(), "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr.get(), kReferenceFontSize);
    cairo_text_extents_t ext;
    cairo_text_extents(cr.get(), "R", &ext);
    if (!(ext.width > 0.0) || !(ext.height > 0.0)) {
        throw RuntimeFailure("letter-R scene: the sans-serif font has no ink for 'R' (no font?)");
    }
    // Map the ink box to [m cols, (1 - m) cols] x [m rows, (1 - m) rows].
    cairo_translate(cr.get(), kLetterMargin * cols, kLetterMargin * rows);
    cairo_scale(cr.get(), (1.0 - 2.0 * kLetterMargin) * cols / ext.width,
                (1.0 - 2.0 * kLetterMargin) * rows / ext.height);
    cairo_move_to(cr.get(), -ext.x_bearing, -ext.y_bearing);
    cairo_text_path(cr.get(), "R");
    cairo_set_source_rgba(cr.get(), 0, 0, 0, 1);
    cairo_fill(cr.get());
    cairo_surface_flush(surface.get());
    if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure(std::string("letter-R scene: Cairo failed: ") +
                             cairo_status_to_string(cairo_status(cr.get())));
    }
    const unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    Plane p(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) p(r, c) = data[r * stride + c] / 255.0;
    return p;
}

}  // namespace pinmask
