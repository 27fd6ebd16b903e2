// The error-against-run-time figure (Cairo): decode time on a log axis (seconds), PSNR (dB) on a
// linear axis, one curve per decoder. Iterative decoders (tv-l2, tvqc, richardson-lucy) are lines
// through their iteration counts, each point labelled with its count; closed forms (wiener,
// tikhonov) are unjoined markers, one per setting, the best labelled with its setting. The
// paper's reference timings (kPaperWienerSeconds, kPaperTvqcSeconds) are dashed vertical lines
// with labels: the paper gives times, not PSNRs on our scenes, so they mark a time only.
// Layout in points/pixels: kPlotWidth x kPlotHeight; the same drawing goes to SVG and PNG.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/error_time.hpp"

namespace pinmask {

inline constexpr int kPlotWidth = 1000;
inline constexpr int kPlotHeight = 640;

struct ErrorTimePlot {
    std::string title;
    std::string subtitle;
    std::vector<ErrorTimePoint> points;  // one SNR; seconds > 0, finite PSNR
};

// Writes the figure to `path` (not atomic: stage it). Throws InvalidInput when there is no point
// with seconds > 0 and a finite PSNR, RuntimeFailure when Cairo fails.
void write_error_time_svg(const std::filesystem::path& path, const ErrorTimePlot& plot);
void write_error_time_png(const std::filesystem::path& path, const ErrorTimePlot& plot);

}  // namespace pinmask
