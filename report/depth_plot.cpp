#include "report/depth_plot.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"
#include "report/plot_canvas.hpp"

namespace pinmask {
namespace {

constexpr int kWidth = 900, kHeight = 560;
constexpr double kLeft = 80, kRight = 30, kTop = 60, kBottom = 70;

double inv(double u) { return std::isinf(u) ? 0.0 : 1.0 / u; }

void label(cairo_t* cr, double x, double y, const std::string& s, double size, double align) {
    plot_label(cr, x, y, s, size, align);
}

void draw(cairo_t* cr, const std::vector<DepthRecord>& recs, double design_u,
          const std::string& title) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    double x_max = 0, y_min = 0, y_max = 0.1;
    for (const auto& r : recs) {
        x_max = std::max(x_max, inv(r.object_distance_m));
        for (double v : {r.wiener_psnr_loss_db, r.tv_psnr_loss_db}) {
            if (std::isfinite(v)) {
                y_min = std::min(y_min, v);
                y_max = std::max(y_max, v);
            }
        }
    }
    if (x_max <= 0) x_max = 1;
    const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
    auto px = [&](double x) { return kLeft + pw * x / (x_max * 1.05); };
    auto py = [&](double y) { return kTop + ph * (1 - (y - y_min) / ((y_max - y_min) * 1.1)); };
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, kLeft, kTop, pw, ph);
    cairo_stroke(cr);
    label(cr, kWidth / 2.0, 30, title, 16, 0.5);
    label(cr, kWidth / 2.0, kHeight - 20, "object distance u (axis linear in 1/u; inf at the left)",
          13, 0.5);
    for (const auto& r : recs) {  // a tick per distance
        const double x = px(inv(r.object_distance_m));
        cairo_move_to(cr, x, kTop + ph);
        cairo_line_to(cr, x, kTop + ph + 5);
        cairo_stroke(cr);
        label(cr, x, kTop + ph + 20, format_length(r.object_distance_m), 10, 0.5);
    }
    for (int k = 0; k <= 5; ++k) {
        const double y = y_min + (y_max - y_min) * 1.1 * k / 5;
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.2f", y);
        label(cr, kLeft - 8, py(y) + 4, buf, 10, 1.0);
    }
    label(cr, 20, kTop - 12, "PSNR loss (dB)", 12, 0.0);
    const double dash[] = {4.0, 4.0};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_move_to(cr, px(inv(design_u)), kTop);
    cairo_line_to(cr, px(inv(design_u)), kTop + ph);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    label(cr, px(inv(design_u)) + 4, kTop + 14, "design u", 10, 0.0);
    const struct {
        bool tv;
        double r, g, b;
        const char* name;
    } curves[] = {{false, 0.1, 0.3, 0.8, "Wiener"}, {true, 0.8, 0.2, 0.1, "TV"}};
    int legend = 0;
    for (const auto& c : curves) {
        bool any = false;
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_set_line_width(cr, 2);
        for (const auto& r : recs) {
            const double v = c.tv ? r.tv_psnr_loss_db : r.wiener_psnr_loss_db;
            if (!std::isfinite(v)) continue;
            const double x = px(inv(r.object_distance_m)), y = py(v);
            any ? cairo_line_to(cr, x, y) : cairo_move_to(cr, x, y);
            any = true;
        }
        if (!any) continue;
        cairo_stroke(cr);
        for (const auto& r : recs) {
            const double v = c.tv ? r.tv_psnr_loss_db : r.wiener_psnr_loss_db;
            if (!std::isfinite(v)) continue;
            cairo_arc(cr, px(inv(r.object_distance_m)), py(v), 3.5, 0, 2 * M_PI);
            cairo_fill(cr);
        }
        cairo_rectangle(cr, kWidth - kRight - 120, kTop + 12 + 18 * legend, 14, 4);
        cairo_fill(cr);
        label(cr, kWidth - kRight - 100, kTop + 18 + 18 * legend, c.name, 12, 0.0);
        ++legend;
    }
}

}  // namespace

void write_depth_svg(const std::filesystem::path& path, const std::vector<DepthRecord>& recs,
                     double design_u, const std::string& title) {
    if (recs.empty()) throw InvalidInput("depth plot: no distances");
    write_plot_svg(path, kWidth, kHeight, "depth plot",
                   [&](cairo_t* cr) { draw(cr, recs, design_u, title); });
}

void write_depth_png(const std::filesystem::path& path, const std::vector<DepthRecord>& recs,
                     double design_u, const std::string& title) {
    if (recs.empty()) throw InvalidInput("depth plot: no distances");
    write_plot_png(path, kWidth, kHeight, "depth plot",
                   [&](cairo_t* cr) { draw(cr, recs, design_u, title); });
}

}  // namespace pinmask
