// Prior scene families besides natural textures (--prior): text pages and star fields.
//   text:  a page of dark glyphs on white paper: lines of random words of random capital and
//          small letters (std::mt19937_64(seed)), Cairo sans-serif, 8 lines per frame height,
//          anti-aliased; paper 1, ink 0.
//   stars: sparse points on a dark sky: about one star per 200 pixels at uniform random
//          positions, brightness 1 / (1 + 9 u^2) for u uniform (a few bright, many faint).
#include <cairo.h>

#include <random>
#include <string>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"
#include "optimize/simulate/scene_cairo.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {
namespace {

constexpr int kTextLines = 8;  // lines per frame height
constexpr double kStarPixelsPerStar = 200.0;

void check_size(int rows, int cols, const char* what) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput(std::string(what) + " scene size " + std::to_string(rows) + " x " +
                           std::to_string(cols) + ": both dimensions must be >= 1");
    }
}

}  // namespace

Plane text_scene(int rows, int cols, std::uint64_t seed) {
    check_size(rows, cols, "text");
    const Plane ink = render_ink_coverage(rows, cols, "text scene", [&](cairo_t* cr) {
        const double line = static_cast<double>(rows) / kTextLines;
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        // Every font option set explicitly: left at their defaults, hinting and metrics are
        // resolved from whatever Cairo drew first in the process (a PDF report turns metric hinting
        // off), so the same seed drew other pages after a report.
        cairo::FontOptionsPtr options(cairo_font_options_create());
        cairo_font_options_set_antialias(options.get(), CAIRO_ANTIALIAS_GRAY);
        cairo_font_options_set_hint_style(options.get(), CAIRO_HINT_STYLE_NONE);
        cairo_font_options_set_hint_metrics(options.get(), CAIRO_HINT_METRICS_OFF);
        cairo_font_options_set_subpixel_order(options.get(), CAIRO_SUBPIXEL_ORDER_DEFAULT);
        cairo_set_font_options(cr, options.get());
        cairo_set_font_size(cr, 0.8 * line);
        cairo_set_source_rgba(cr, 0, 0, 0, 1);
        std::mt19937_64 rng(seed);
        std::uniform_int_distribution<int> letter(0, 51), word_length(1, 8);
        for (int l = 0; l < kTextLines; ++l) {
            std::string text;
            while (static_cast<int>(text.size()) < cols / 4 + 8) {
                const int len = word_length(rng);
                for (int i = 0; i < len; ++i) {
                    const int c = letter(rng);
                    text.push_back(static_cast<char>(c < 26 ? 'A' + c : 'a' + (c - 26)));
                }
                text.push_back(' ');
            }
            cairo_move_to(cr, 0.02 * cols, (l + 0.8) * line);
            cairo_show_text(cr, text.c_str());
        }
    });
    return 1.0 - ink;  // paper 1, ink 0
}

Plane stars_scene(int rows, int cols, std::uint64_t seed) {
    check_size(rows, cols, "stars");
    Plane p = Plane::Zero(rows, cols);
    std::mt19937_64 rng(seed);
    const double pixels = static_cast<double>(rows) * cols;
    const long long count = std::max(1LL, static_cast<long long>(pixels / kStarPixelsPerStar));
    std::uniform_int_distribution<int> r(0, rows - 1), c(0, cols - 1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (long long i = 0; i < count; ++i) {
        const int rr = r(rng), cc = c(rng);
        const double v = u(rng);
        p(rr, cc) = std::max(p(rr, cc), 1.0 / (1.0 + 9.0 * v * v));
    }
    return p;
}

}  // namespace pinmask
