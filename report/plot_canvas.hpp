// The Cairo canvas of the line plots (depth, pinhole count, sweep): a figure drawn by a
// callback onto an SVG or PNG of a given size, with Cairo's errors as exceptions naming the plot
// and the file, and the text label every plot places.
#pragma once

#include <cairo.h>

#include <filesystem>
#include <functional>
#include <string>

namespace pinmask {

using PlotDraw = std::function<void(cairo_t*)>;

// `what` names the plot in errors ("depth plot"); RuntimeFailure when Cairo fails.
void write_plot_svg(const std::filesystem::path& path, int width, int height,
                    const std::string& what, const PlotDraw& draw);
void write_plot_png(const std::filesystem::path& path, int width, int height,
                    const std::string& what, const PlotDraw& draw);

// Text of `size` points at (x, y) on the baseline, aligned by `align` of its width (0 left,
// 0.5 centred, 1 right).
void plot_label(cairo_t* cr, double x, double y, const std::string& s, double size, double align);

}  // namespace pinmask
