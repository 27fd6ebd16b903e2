// The letter-R scene: Cairo renders the outline of a bold sans-serif "R" into an 8-bit alpha
// surface; the ink box is stretched to the frame minus kLetterMargin on each side.
#include <cairo.h>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"
#include "optimize/simulate/scene_cairo.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {
namespace {

constexpr double kReferenceFontSize = 100.0;  // user units; only the ratio to the ink box matters

}  // namespace

Plane letter_r_scene(int rows, int cols) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput("scene size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
    return render_ink_coverage(rows, cols, "letter-R scene", [&](cairo_t* cr) {
        cairo::FontOptionsPtr options(cairo_font_options_create());
        // Unhinted outlines: the glyph shape does not snap to the pixel grid, so it scales
        // smoothly.
        cairo_font_options_set_hint_style(options.get(), CAIRO_HINT_STYLE_NONE);
        cairo_font_options_set_hint_metrics(options.get(), CAIRO_HINT_METRICS_OFF);
        cairo_font_options_set_antialias(options.get(), CAIRO_ANTIALIAS_GRAY);
        cairo_set_font_options(cr, options.get());
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
        cairo_set_font_size(cr, kReferenceFontSize);
        cairo_text_extents_t ext;
        cairo_text_extents(cr, "R", &ext);
        if (!(ext.width > 0.0) || !(ext.height > 0.0)) {
            throw RuntimeFailure(
                "letter-R scene: the sans-serif font has no ink for 'R' (no font?)");
        }
        // Map the ink box to [m cols, (1 - m) cols] x [m rows, (1 - m) rows].
        cairo_translate(cr, kLetterMargin * cols, kLetterMargin * rows);
        cairo_scale(cr, (1.0 - 2.0 * kLetterMargin) * cols / ext.width,
                    (1.0 - 2.0 * kLetterMargin) * rows / ext.height);
        cairo_move_to(cr, -ext.x_bearing, -ext.y_bearing);
        cairo_text_path(cr, "R");
        cairo_set_source_rgba(cr, 0, 0, 0, 1);
        cairo_fill(cr);
    });
}

}  // namespace pinmask
