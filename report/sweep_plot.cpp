#include "report/sweep_plot.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "core/errors/error.hpp"
#include "report/plot_canvas.hpp"

namespace pinmask {
namespace {

constexpr int kWidth = 900, kHeight = 560;
constexpr double kLeft = 80, kRight = 230, kTop = 60, kBottom = 70;
constexpr int kTicks = 5;

void label(cairo_t* cr, double x, double y, const std::string& s, double size, double align) {
    plot_label(cr, x, y, s, size, align);
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

struct Range {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    void add(double v) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    void pad() {  // a flat range gets a width, every range a margin
        if (hi - lo <= 1e-12 * std::max(1.0, std::abs(hi))) {
            lo -= 0.5;
            hi += 0.5;
        }
        const double m = 0.05 * (hi - lo);
        lo -= m;
        hi += m;
    }
};

void draw(cairo_t* cr, const SweepPlot& plot) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    Range xr, yr;
    bool positive = true;
    for (const auto& s : plot.series) {
        for (const auto& [x, y] : s.points) {
            if (!std::isfinite(x) || !std::isfinite(y)) continue;
            xr.add(x);
            yr.add(y);
            positive = positive && x > 0;
        }
    }
    const bool log_x = positive && xr.hi / xr.lo > kLogAxisSpan;
    const auto tx = [&](double x) { return log_x ? std::log10(x) : x; };
    Range xa;
    xa.add(tx(xr.lo));
    xa.add(tx(xr.hi));
    xa.pad();
    yr.pad();
    const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
    auto px = [&](double x) { return kLeft + pw * (tx(x) - xa.lo) / (xa.hi - xa.lo); };
    auto py = [&](double y) { return kTop + ph * (1 - (y - yr.lo) / (yr.hi - yr.lo)); };
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, kLeft, kTop, pw, ph);
    cairo_stroke(cr);
    label(cr, (kLeft + kLeft + pw) / 2.0, 30, plot.title, 16, 0.5);
    label(cr, (kLeft + kLeft + pw) / 2.0, kHeight - 20, plot.x_label + (log_x ? " (log axis)" : ""),
          13, 0.5);
    label(cr, 20, kTop - 12, plot.y_label, 12, 0.0);
    for (int k = 0; k <= kTicks; ++k) {
        const double a = xa.lo + (xa.hi - xa.lo) * k / kTicks;
        const double x = kLeft + pw * k / kTicks;
        cairo_move_to(cr, x, kTop + ph);
        cairo_line_to(cr, x, kTop + ph + 5);
        cairo_stroke(cr);
        label(cr, x, kTop + ph + 20, number(log_x ? std::pow(10.0, a) : a), 10, 0.5);
        const double y = yr.lo + (yr.hi - yr.lo) * k / kTicks;
        label(cr, kLeft - 8, py(y) + 4, number(y), 10, 1.0);
    }
    static const double kColours[][3] = {{0.1, 0.3, 0.8}, {0.8, 0.2, 0.1}, {0.1, 0.6, 0.2},
                                         {0.6, 0.2, 0.7}, {0.9, 0.6, 0.0}, {0.2, 0.6, 0.7},
                                         {0.5, 0.5, 0.5}, {0.0, 0.0, 0.0}};
    constexpr int kColourCount = sizeof kColours / sizeof kColours[0];
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
        const double* c = kColours[i % kColourCount];
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_set_line_width(cr, 2);
        auto pts = plot.series[i].points;
        std::stable_sort(pts.begin(), pts.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        bool any = false;
        for (const auto& [x, y] : pts) {
            if (!std::isfinite(x) || !std::isfinite(y)) continue;
            any ? cairo_line_to(cr, px(x), py(y)) : cairo_move_to(cr, px(x), py(y));
            any = true;
        }
        if (!any) continue;
        cairo_stroke(cr);
        for (const auto& [x, y] : pts) {
            if (!std::isfinite(x) || !std::isfinite(y)) continue;
            cairo_arc(cr, px(x), py(y), 3.5, 0, 2 * M_PI);
            cairo_fill(cr);
        }
        if (plot.series[i].label.empty()) continue;
        const double ly = kTop + 12 + 18 * static_cast<double>(i);
        if (ly > kTop + ph) continue;  // more series than the legend holds
        cairo_rectangle(cr, kWidth - kRight + 15, ly - 6, 14, 4);
        cairo_fill(cr);
        label(cr, kWidth - kRight + 35, ly, plot.series[i].label, 11, 0.0);
    }
}

void require_points(const SweepPlot& plot) {
    for (const auto& s : plot.series)
        for (const auto& [x, y] : s.points)
            if (std::isfinite(x) && std::isfinite(y)) return;
    throw InvalidInput("sweep plot '" + plot.title + "': no finite point to draw");
}

}  // namespace

void write_sweep_plot_svg(const std::filesystem::path& path, const SweepPlot& plot) {
    require_points(plot);
    write_plot_svg(path, kWidth, kHeight, "sweep plot", [&](cairo_t* cr) { draw(cr, plot); });
}

void write_sweep_plot_png(const std::filesystem::path& path, const SweepPlot& plot) {
    require_points(plot);
    write_plot_png(path, kWidth, kHeight, "sweep plot", [&](cairo_t* cr) { draw(cr, plot); });
}

}  // namespace pinmask
