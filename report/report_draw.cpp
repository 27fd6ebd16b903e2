#include "report/report_draw.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"

namespace pinmask::report_draw {
namespace {

constexpr double kFrameWidth = 0.5;  // pt, frame around images and colour bars
constexpr int kRampSteps = 256;      // colour bar: one column per grey level

void select_font(cairo_t* cr, const Font& font) {
    cairo_select_font_face(cr, "sans-serif",
                           font.italic ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                           font.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, font.size);
}

void frame(cairo_t* cr, const Box& b) {
    cairo_save(cr);
    cairo_set_source_rgb(cr, kRuleGrey, kRuleGrey, kRuleGrey);
    cairo_set_line_width(cr, kFrameWidth);
    cairo_rectangle(cr, b.x - kFrameWidth / 2, b.y - kFrameWidth / 2, b.w + kFrameWidth,
                    b.h + kFrameWidth);
    cairo_stroke(cr);
    cairo_restore(cr);
}

}  // namespace

void prepare_context(cairo_t* cr) {
    cairo_font_options_t* fo = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
    cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
    cairo_set_font_options(cr, fo);
    cairo_font_options_destroy(fo);
    cairo_set_source_rgb(cr, kInk, kInk, kInk);
}

Measure::Measure()
    : surface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1)), cr_(cairo_create(surface_)) {
    prepare_context(cr_);
}

Measure::~Measure() {
    cairo_destroy(cr_);
    cairo_surface_destroy(surface_);
}

double text_width(cairo_t* cr, const std::string& s, const Font& font) {
    select_font(cr, font);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    return e.x_advance;
}

void draw_text(cairo_t* cr, double x, double y, const std::string& s, const Font& font,
               double align) {
    if (s.empty()) return;
    const double w = text_width(cr, s, font);  // selects the font
    cairo_move_to(cr, x - align * w, y);
    cairo_show_text(cr, s.c_str());
    cairo_new_path(cr);
}

std::string fit_text(cairo_t* cr, const std::string& s, const Font& font, double max_width) {
    if (text_width(cr, s, font) <= max_width) return s;
    // Drop whole UTF-8 characters from the end until the text and the ellipsis fit.
    std::string t = s;
    while (!t.empty()) {
        do {
            t.pop_back();
        } while (!t.empty() && (static_cast<unsigned char>(t.back()) & 0xC0) == 0x80);
        if (!t.empty() && (static_cast<unsigned char>(t.back()) & 0xC0) == 0xC0) t.pop_back();
        if (text_width(cr, t + "...", font) <= max_width) return t + "...";
    }
    return "...";
}

std::vector<std::string> wrap_text(cairo_t* cr, const std::string& s, const Font& font,
                                   double max_width) {
    std::vector<std::string> lines;
    std::istringstream in(s);
    std::string word, line;
    while (in >> word) {
        const std::string candidate = line.empty() ? word : line + " " + word;
        if (line.empty() || text_width(cr, candidate, font) <= max_width) {
            line = candidate;
            continue;
        }
        lines.push_back(fit_text(cr, line, font, max_width));
        line = word;
    }
    lines.push_back(fit_text(cr, line, font, max_width));
    return lines;
}

std::uint8_t grey_level(double v, double lo, double hi) {
    double t = (v - lo) / (hi - lo);
    if (std::isnan(t)) t = 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return static_cast<std::uint8_t>(std::lround(255.0 * t));
}

Box draw_plane(cairo_t* cr, const Plane& values, double lo, double hi, const Box& area) {
    const int rows = static_cast<int>(values.rows()), cols = static_cast<int>(values.cols());
    cairo::SurfacePtr img(cairo_image_surface_create(CAIRO_FORMAT_RGB24, cols, rows));
    if (cairo_surface_status(img.get()) != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure("report panel of " + std::to_string(rows) + " x " +
                             std::to_string(cols) + " pixels: cairo could not allocate it");
    }
    cairo_surface_flush(img.get());
    unsigned char* data = cairo_image_surface_get_data(img.get());
    const int stride = cairo_image_surface_get_stride(img.get());
    for (int r = 0; r < rows; ++r) {
        auto* row =
            reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(r) * stride);
        for (int c = 0; c < cols; ++c) {
            const std::uint32_t g = grey_level(values(r, c), lo, hi);
            row[c] = (g << 16) | (g << 8) | g;
        }
    }
    cairo_surface_mark_dirty(img.get());

    const double scale = std::min(area.w / cols, area.h / rows);
    const Box box{area.x + (area.w - scale * cols) / 2, area.y, scale * cols, scale * rows};
    cairo_save(cr);
    cairo_rectangle(cr, box.x, box.y, box.w, box.h);
    cairo_clip(cr);
    cairo_translate(cr, box.x, box.y);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, img.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    frame(cr, box);
    return box;
}

void draw_colorbar(cairo_t* cr, const Box& bar, double lo, double hi, const std::string& unit,
                   const Font& font) {
    cairo::SurfacePtr ramp(cairo_image_surface_create(CAIRO_FORMAT_RGB24, kRampSteps, 1));
    cairo_surface_flush(ramp.get());
    auto* px = reinterpret_cast<std::uint32_t*>(cairo_image_surface_get_data(ramp.get()));
    for (std::uint32_t g = 0; g < kRampSteps; ++g) px[g] = (g << 16) | (g << 8) | g;
    cairo_surface_mark_dirty(ramp.get());
    cairo_save(cr);
    cairo_rectangle(cr, bar.x, bar.y, bar.w, bar.h);
    cairo_clip(cr);
    cairo_translate(cr, bar.x, bar.y);
    cairo_scale(cr, bar.w / kRampSteps, bar.h);
    cairo_set_source_surface(cr, ramp.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    frame(cr, bar);
    const std::string suffix = unit.empty() ? "" : " " + unit;
    const double y = bar.y + bar.h + font.size + 1.0;
    draw_text(cr, bar.x, y, short_number(lo) + suffix, font, 0.0);
    draw_text(cr, bar.x + bar.w, y, short_number(hi) + suffix, font, 1.0);
}

std::string short_number(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

}  // namespace pinmask::report_draw
