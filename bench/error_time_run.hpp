// `pinmask bench error-time` as library calls: the paper preset mask, the set-up (the
// mask's PSF of one period and the scenes rendered at it), and the sweep with its means, best
// points per decoder, Markdown table and one plot per SNR. Never prints.
#pragma once

#include <string>
#include <vector>

#include "bench/error_time.hpp"
#include "bench/error_time_plot.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {

// The paper preset = `pinmask generate --family paper --seed 1` (8 pixels per cell).
Mask error_time_paper_mask();

struct ErrorTimeSetup {
    Kernel kernel;  // the pinhole kernel of the PSF
    Plane psf;      // one period, m x m
    int period_px = 0;
    std::vector<NamedScene> scenes;  // rendered at m x m
};

ErrorTimeSetup error_time_setup(const Mask& mask, const std::vector<SceneSpec>& scenes);

struct ErrorTimeNamedPlot {
    std::string stem;  // error_time_snrS
    ErrorTimePlot plot;
};

struct ErrorTimeResult {
    std::vector<ErrorTimeRecord> records;   // every scene and setting
    std::vector<ErrorTimePoint> points;     // means over scenes
    std::vector<DecoderSummary> summary;    // best and near-best point per decoder
    std::string markdown;                   // the table of the summary
    std::vector<ErrorTimeNamedPlot> plots;  // one per SNR, in options.snr_db order
};

// Runs the sweep (options validated by run_error_time). `mask_source` names the mask in the
// plots' subtitles.
ErrorTimeResult run_error_time_bench(const ErrorTimeSetup& setup, const ErrorTimeOptions& options,
                                     const std::string& mask_source);

// %g of v (the SNR in file stems and titles).
std::string error_time_number(double v);

}  // namespace pinmask
