// The sweep figures (Cairo): a quantity (PSNR, dB) against one varied key (K, pinhole size,
// light level), one polyline with markers per combination of the other varied keys. The x axis
// is logarithmic when every x is positive and they span more than kLogAxisSpan, else linear.
// Same drawing to SVG and PNG (the approach of report/depth_plot).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace pinmask {

// x/max(x) ratio above which the x axis becomes logarithmic (light levels span decades).
inline constexpr double kLogAxisSpan = 20.0;

struct PlotSeries {
    std::string label;                              // "" when only one series
    std::vector<std::pair<double, double>> points;  // (x, y), drawn in x order
};

struct SweepPlot {
    std::string title, x_label, y_label;
    std::vector<PlotSeries> series;
};

// Not atomic: stage the paths. InvalidInput without a finite point, RuntimeFailure when Cairo
// fails.
void write_sweep_plot_svg(const std::filesystem::path& path, const SweepPlot& plot);
void write_sweep_plot_png(const std::filesystem::path& path, const SweepPlot& plot);

}  // namespace pinmask
