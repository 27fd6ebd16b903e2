#include "report/holes_plot.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/errors/error.hpp"
#include "report/plot_canvas.hpp"

namespace pinmask {
namespace {

constexpr int kWidth = 900, kHeight = 560;
constexpr double kLeft = 80, kRight = 90, kTop = 60, kBottom = 90;

void label(cairo_t* cr, double x, double y, const std::string& s, double size, double align) {
    plot_label(cr, x, y, s, size, align);
}

std::string number(double v, const char* spec) {
    char buf[32];
    std::snprintf(buf, sizeof buf, spec, v);
    return buf;
}

void draw(cairo_t* cr, const std::vector<HolesPoint>& pts, const std::string& title) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    int k_min = pts.front().holes, k_max = pts.front().holes;
    double y_min = INFINITY, y_max = -INFINITY;
    for (const auto& p : pts) {
        k_min = std::min(k_min, p.holes);
        k_max = std::max(k_max, p.holes);
        if (std::isfinite(p.psnr_db)) {
            y_min = std::min(y_min, p.psnr_db);
            y_max = std::max(y_max, p.psnr_db);
        }
    }
    if (!std::isfinite(y_min)) y_min = 0, y_max = 1;
    if (y_max - y_min < 0.1) y_min -= 0.05, y_max += 0.05;
    const double pad = 0.05 * (y_max - y_min);
    y_min -= pad;
    y_max += pad;
    const double x0 = k_min - 0.5, x1 = k_max + 0.5;
    const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
    auto px = [&](double k) { return kLeft + pw * (k - x0) / (x1 - x0); };
    auto py = [&](double y) { return kTop + ph * (1 - (y - y_min) / (y_max - y_min)); };
    auto pg = [&](double k) { return kTop + ph * (1 - k / (k_max * 1.05)); };  // light gain axis
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, kLeft, kTop, pw, ph);
    cairo_stroke(cr);
    label(cr, kWidth / 2.0, 30, title, 16, 0.5);
    label(cr, kWidth / 2.0, kTop + ph + 40, "pinholes K", 13, 0.5);
    const int step = std::max(1, (k_max - k_min + 1) / 12);
    for (int k = k_min; k <= k_max; k += step) {
        cairo_move_to(cr, px(k), kTop + ph);
        cairo_line_to(cr, px(k), kTop + ph + 5);
        cairo_stroke(cr);
        label(cr, px(k), kTop + ph + 20, std::to_string(k), 10, 0.5);
    }
    for (int t = 0; t <= 5; ++t) {
        const double y = y_min + (y_max - y_min) * t / 5;
        label(cr, kLeft - 8, py(y) + 4, number(y, "%.2f"), 10, 1.0);
        const double g = k_max * 1.05 * t / 5;
        label(cr, kLeft + pw + 8, pg(g) + 4, number(g, "%.0f"), 10, 0.0);
    }
    label(cr, 20, kTop - 12, "predicted PSNR (dB)", 12, 0.0);
    label(cr, kWidth - 10, kTop - 12, "light gain (x one pinhole)", 12, 1.0);
    // Light gain K: dashed grey.
    const double dash[] = {5.0, 4.0};
    cairo_set_source_rgb(cr, 0.5, 0.5, 0.5);
    cairo_set_line_width(cr, 1.5);
    cairo_set_dash(cr, dash, 2, 0);
    cairo_move_to(cr, px(k_min), pg(k_min));
    cairo_line_to(cr, px(k_max), pg(k_max));
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    // Predicted PSNR of the best mask per K.
    cairo_set_source_rgb(cr, 0.1, 0.3, 0.8);
    cairo_set_line_width(cr, 2);
    bool any = false;
    for (const auto& p : pts) {
        if (!std::isfinite(p.psnr_db)) continue;
        any ? cairo_line_to(cr, px(p.holes), py(p.psnr_db))
            : cairo_move_to(cr, px(p.holes), py(p.psnr_db));
        any = true;
    }
    cairo_stroke(cr);
    for (const auto& p : pts) {
        if (!std::isfinite(p.psnr_db)) continue;
        cairo_arc(cr, px(p.holes), py(p.psnr_db), 3.5, 0, 2 * M_PI);
        cairo_fill(cr);
    }
    const auto best = std::max_element(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
        const double va = std::isfinite(a.psnr_db) ? a.psnr_db : -INFINITY;
        const double vb = std::isfinite(b.psnr_db) ? b.psnr_db : -INFINITY;
        return va < vb;
    });
    if (std::isfinite(best->psnr_db)) {
        // Centred over the point, but kept inside the plot near either side (the right axis's
        // ticks sit just outside it).
        const double at = (px(best->holes) - kLeft) / pw;
        const double anchor = at > 0.85 ? 1.0 : at < 0.15 ? 0.0 : 0.5;
        label(cr, px(best->holes), py(best->psnr_db) - 10,
              "best K = " + std::to_string(best->holes), 11, anchor);
    }
    // Legend under the axis title row, outside the data area.
    const double ly = kHeight - 18;
    cairo_rectangle(cr, kLeft, ly - 5, 14, 4);
    cairo_fill(cr);
    label(cr, kLeft + 20, ly, "predicted PSNR, best mask at K", 12, 0.0);
    cairo_set_source_rgb(cr, 0.5, 0.5, 0.5);
    cairo_rectangle(cr, kLeft + 300, ly - 4, 14, 2);
    cairo_fill(cr);
    label(cr, kLeft + 320, ly, "light gain K (right axis)", 12, 0.0);
}

void check_points(const std::vector<HolesPoint>& pts) {
    if (pts.empty()) throw InvalidInput("holes plot: no pinhole counts");
    for (const auto& p : pts) {
        if (p.holes < 1) {
            throw invalid_field("holes", std::to_string(p.holes), "must be >= 1 in the plot");
        }
    }
}

}  // namespace

void write_holes_svg(const std::filesystem::path& path, const std::vector<HolesPoint>& pts,
                     const std::string& title) {
    check_points(pts);
    write_plot_svg(path, kWidth, kHeight, "holes plot", [&](cairo_t* cr) { draw(cr, pts, title); });
}

void write_holes_png(const std::filesystem::path& path, const std::vector<HolesPoint>& pts,
                     const std::string& title) {
    check_points(pts);
    write_plot_png(path, kWidth, kHeight, "holes plot", [&](cairo_t* cr) { draw(cr, pts, title); });
}

}  // namespace pinmask
