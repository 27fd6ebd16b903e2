#include "bench/error_time_plot.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"

namespace pinmask {
namespace {

using cairo::ContextPtr;
using cairo::SurfacePtr;

// Plot frame inside the canvas (pixels): room for axis labels left/bottom, legend right.
constexpr double kLeft = 80, kRight = 220, kTop = 70, kBottom = 70;
constexpr double kFontSize = 14, kSmallFont = 11, kTitleFont = 18;

struct Rgb {
    double r, g, b;
};

struct Style {
    const char* decoder;
    const char* label;
    Rgb colour;
    bool iterative;
};

// Okabe-Ito colours: distinguishable with common colour-vision deficiencies.
const Style kStyles[] = {
    {"wiener", "Wiener (NSR sweep)", {0.0, 0.45, 0.70}, false},
    {"tikhonov", "Tikhonov (lambda sweep)", {0.90, 0.62, 0.0}, false},
    {"tv-l2", "TV-L2 ADMM", {0.0, 0.62, 0.45}, true},
    {"tvqc", "TVQC (paper's decoder)", {0.84, 0.37, 0.0}, true},
    {"richardson-lucy", "Richardson-Lucy", {0.80, 0.47, 0.65}, true},
};

std::string short_num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string seconds_label(double decade) {
    const double v = std::pow(10.0, decade);
    return short_num(v) + " s";
}

class Frame {
  public:
    Frame(double x0, double x1, double y0, double y1) : x0_(x0), x1_(x1), y0_(y0), y1_(y1) {}
    // Canvas coordinates of (log10 seconds, PSNR).
    double px(double log_s) const {
        return kLeft + (log_s - x0_) / (x1_ - x0_) * (kPlotWidth - kLeft - kRight);
    }
    double py(double db) const {
        return kPlotHeight - kBottom - (db - y0_) / (y1_ - y0_) * (kPlotHeight - kTop - kBottom);
    }
    double x0_, x1_, y0_, y1_;
};

void text(cairo_t* cr, double x, double y, const std::string& s, double size, double align_x,
          double align_y) {
    cairo_set_font_size(cr, size);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    cairo_move_to(cr, x - align_x * e.width - e.x_bearing, y - align_y * e.height - e.y_bearing);
    cairo_show_text(cr, s.c_str());
}

void marker(cairo_t* cr, double x, double y, bool square) {
    if (square) {
        cairo_rectangle(cr, x - 4.5, y - 4.5, 9, 9);
    } else {
        cairo_new_sub_path(cr);
        cairo_arc(cr, x, y, 4.0, 0, 2 * M_PI);
    }
    cairo_fill(cr);
}

std::vector<ErrorTimePoint> usable(const std::vector<ErrorTimePoint>& points) {
    std::vector<ErrorTimePoint> out;
    for (const auto& p : points)
        if (p.seconds > 0.0 && std::isfinite(p.seconds) && std::isfinite(p.psnr_db))
            out.push_back(p);
    if (out.empty()) {
        throw InvalidInput("error-time plot: no point with a positive time and a finite PSNR");
    }
    return out;
}

void draw(cairo_t* cr, const ErrorTimePlot& plot) {
    const std::vector<ErrorTimePoint> pts = usable(plot.points);
    double tmin = std::min(kPaperWienerSeconds, kPaperTvqcSeconds), tmax = kPaperTvqcSeconds;
    double dbmin = pts[0].psnr_db, dbmax = pts[0].psnr_db;
    for (const auto& p : pts) {
        tmin = std::min(tmin, p.seconds);
        tmax = std::max(tmax, p.seconds);
        dbmin = std::min(dbmin, p.psnr_db);
        dbmax = std::max(dbmax, p.psnr_db);
    }
    const double y_step = (dbmax - dbmin) > 12 ? 5.0 : 2.0;
    double y0 = std::floor(dbmin / y_step) * y_step, y1 = std::ceil(dbmax / y_step) * y_step;
    if (dbmin - y0 < 0.5) y0 -= y_step;  // keep markers off the frame
    if (y1 - dbmax < 1.0) y1 += y_step;  // room for the iteration labels
    const Frame f(std::floor(std::log10(tmin)), std::ceil(std::log10(tmax)), y0, y1);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);

    // Grid: decades and their 2..9 multiples on x, every y_step dB on y.
    cairo_set_line_width(cr, 1.0);
    for (double d = f.x0_; d <= f.x1_ + 1e-9; d += 1.0) {
        for (int m = 1; m <= 9 && (m == 1 || d < f.x1_); ++m) {
            const double x = f.px(d + std::log10(m));
            cairo_set_source_rgb(cr, m == 1 ? 0.78 : 0.92, m == 1 ? 0.78 : 0.92,
                                 m == 1 ? 0.78 : 0.92);
            cairo_move_to(cr, x, f.py(f.y0_));
            cairo_line_to(cr, x, f.py(f.y1_));
            cairo_stroke(cr);
        }
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        text(cr, f.px(d), f.py(f.y0_) + 8, seconds_label(d), kFontSize, 0.5, 0.0);
    }
    for (double y = f.y0_; y <= f.y1_ + 1e-9; y += y_step) {
        cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
        cairo_move_to(cr, f.px(f.x0_), f.py(y));
        cairo_line_to(cr, f.px(f.x1_), f.py(y));
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        text(cr, f.px(f.x0_) - 8, f.py(y), short_num(y), kFontSize, 1.0, 0.5);
    }
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_rectangle(cr, f.px(f.x0_), f.py(f.y1_), f.px(f.x1_) - f.px(f.x0_),
                    f.py(f.y0_) - f.py(f.y1_));
    cairo_stroke(cr);
    text(cr, (f.px(f.x0_) + f.px(f.x1_)) / 2, kPlotHeight - 22,
         "decode time: CPU seconds on one thread (log scale)", kFontSize, 0.5, 0.5);
    cairo_save(cr);
    cairo_translate(cr, 24, (f.py(f.y0_) + f.py(f.y1_)) / 2);
    cairo_rotate(cr, -M_PI / 2);
    text(cr, 0, 0, "PSNR (dB), mean over scenes", kFontSize, 0.5, 0.5);
    cairo_restore(cr);
    text(cr, kLeft, 22, plot.title, kTitleFont, 0.0, 0.5);
    text(cr, kLeft, 46, plot.subtitle, kSmallFont + 1, 0.0, 0.5);

    // The paper's reference timings.
    const std::pair<double, const char*> refs[] = {{kPaperWienerSeconds, "paper: Wiener 0.004 s"},
                                                   {kPaperTvqcSeconds, "paper: TVQC 7.2 s"}};
    for (const auto& [t, label] : refs) {
        const double x = f.px(std::log10(t));
        cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
        const double dash[] = {6.0, 4.0};
        cairo_set_dash(cr, dash, 2, 0);
        cairo_set_line_width(cr, 1.5);
        cairo_move_to(cr, x, f.py(f.y0_));
        cairo_line_to(cr, x, f.py(f.y1_));
        cairo_stroke(cr);
        cairo_set_dash(cr, nullptr, 0, 0);
        cairo_save(cr);
        cairo_translate(cr, x - 4, f.py(f.y1_) + 6);
        cairo_rotate(cr, -M_PI / 2);  // reads upwards, just left of the line
        text(cr, 0, 0, label, kSmallFont + 1, 1.0, 1.0);
        cairo_restore(cr);
    }

    // Curves.
    double legend_y = kTop + 10;
    for (const Style& st : kStyles) {
        std::vector<ErrorTimePoint> c;
        for (const auto& p : pts)
            if (p.decoder == st.decoder) c.push_back(p);
        if (c.empty()) continue;
        cairo_set_source_rgb(cr, st.colour.r, st.colour.g, st.colour.b);
        cairo_set_line_width(cr, 2.0);
        if (st.iterative) {
            std::sort(c.begin(), c.end(),
                      [](const auto& a, const auto& b) { return a.iterations < b.iterations; });
            for (std::size_t i = 0; i < c.size(); ++i) {
                const double x = f.px(std::log10(c[i].seconds)), y = f.py(c[i].psnr_db);
                i == 0 ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y);
            }
            cairo_stroke(cr);
            for (const auto& p : c) {
                const double x = f.px(std::log10(p.seconds)), y = f.py(p.psnr_db);
                marker(cr, x, y, false);
                text(cr, x + 5, y - 5, std::to_string(p.iterations), kSmallFont, 0.0, 1.0);
            }
        } else {
            const ErrorTimePoint* best = &c[0];
            for (const auto& p : c) {
                marker(cr, f.px(std::log10(p.seconds)), f.py(p.psnr_db), true);
                if (p.psnr_db > best->psnr_db) best = &p;
            }
            // Left of the marker: the closed forms are the fastest points, the left is free.
            text(cr, f.px(std::log10(best->seconds)) - 8, f.py(best->psnr_db),
                 best->parameter + " " + short_num(best->value), kSmallFont, 1.0, 0.5);
        }
        // Legend entry.
        const double lx = kPlotWidth - kRight + 16;
        cairo_move_to(cr, lx, legend_y);
        cairo_line_to(cr, lx + 24, legend_y);
        if (st.iterative) cairo_stroke(cr);
        cairo_new_path(cr);
        marker(cr, lx + 12, legend_y, !st.iterative);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        text(cr, lx + 32, legend_y, st.label, kSmallFont, 0.0, 0.5);
        legend_y += 24;
    }
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    const double lx = kPlotWidth - kRight + 16;
    text(cr, lx, legend_y + 6, "numbers: iterations", kSmallFont, 0.0, 0.5);
    text(cr, lx, legend_y + 24, "squares: one per setting,", kSmallFont, 0.0, 0.5);
    text(cr, lx, legend_y + 40, "best one labelled", kSmallFont, 0.0, 0.5);
}

void check(cairo_t* cr, cairo_surface_t* s, const std::filesystem::path& path) {
    cairo_surface_flush(s);
    const cairo_status_t st =
        cairo_status(cr) != CAIRO_STATUS_SUCCESS ? cairo_status(cr) : cairo_surface_status(s);
    if (st != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure("error-time plot " + path.string() + ": " +
                             cairo_status_to_string(st));
    }
}

}  // namespace

void write_error_time_svg(const std::filesystem::path& path, const ErrorTimePlot& plot) {
    usable(plot.points);
    SurfacePtr s(cairo_svg_surface_create(path.c_str(), kPlotWidth, kPlotHeight));
    ContextPtr cr(cairo_create(s.get()));
    draw(cr.get(), plot);
    check(cr.get(), s.get(), path);
    cr.reset();
    cairo_surface_finish(s.get());
    if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure("error-time plot " + path.string() + ": " +
                             cairo_status_to_string(cairo_surface_status(s.get())));
    }
}

void write_error_time_png(const std::filesystem::path& path, const ErrorTimePlot& plot) {
    usable(plot.points);
    SurfacePtr s(cairo_image_surface_create(CAIRO_FORMAT_RGB24, kPlotWidth, kPlotHeight));
    ContextPtr cr(cairo_create(s.get()));
    draw(cr.get(), plot);
    check(cr.get(), s.get(), path);
    const cairo_status_t st = cairo_surface_write_to_png(s.get(), path.c_str());
    if (st != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure("error-time plot " + path.string() + ": " +
                             cairo_status_to_string(st));
    }
}

}  // namespace pinmask
