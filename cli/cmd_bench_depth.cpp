// `pinmask bench depth`: the cost of `pinmask depth` on a 1920 x 1200 sensor beside an FFT pair
// of that size, timed in the same run.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/depth_bench.hpp"
#include "cli/commands.hpp"
#include "core/fft/fft.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    DepthBenchOptions bench;
    bool no_tv = false;
    bool json = false;
};

void run(Options o) {
    o.bench.with_tv = !o.no_tv;
    o.bench.threads = fft_threads();  // as pinmask depth
    if (!o.json) {
        std::fprintf(stderr, "running depth at %d distances, then %d FFT pair(s)...\n",
                     o.bench.distances, o.bench.repeat);
    }
    const DepthBenchResult r = bench_depth(o.bench);
    const double ratio = r.depth_seconds / r.fft_pair_seconds;
    if (o.json) {
        std::cout << nlohmann::json{{"period_px", r.period_px},
                                    {"distances", r.distances},
                                    {"threads", o.bench.threads},
                                    {"tv", o.bench.with_tv},
                                    {"depth_seconds", r.depth_seconds},
                                    {"depth_cpu_seconds", r.depth_cpu_seconds},
                                    {"fft_rows", o.bench.rows},
                                    {"fft_cols", o.bench.cols},
                                    {"fft_pair_seconds", r.fft_pair_seconds},
                                    {"fft_pair_cpu_seconds", r.fft_pair_cpu_seconds},
                                    {"depth_over_fft_pair", ratio},
                                    {"worst_wiener_loss_db", r.worst_wiener_loss_db}}
                         .dump()
                  << "\n";
        return;
    }
    std::printf(
        "NIR camera, %d px period, %d distances 0.9-2 m, photons 20, read noise 6 e-%s, "
        "%d thread(s)\n",
        r.period_px, r.distances, o.bench.with_tv ? ", Wiener + TV" : ", Wiener only",
        o.bench.threads);
    std::printf("  depth                       %9.3f s wall  %9.3f s CPU\n", r.depth_seconds,
                r.depth_cpu_seconds);
    std::printf(
        "  FFT pair %4d x %-4d         %9.3g s wall  %9.3g s CPU   depth / FFT pair = %.0f\n",
        o.bench.rows, o.bench.cols, r.fft_pair_seconds, r.fft_pair_cpu_seconds, ratio);
    std::printf("  (largest Wiener loss of the run %.2f dB)\n", r.worst_wiener_loss_db);
}

}  // namespace

void add_bench_depth(CLI::App& bench) {
    auto opts = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "depth",
        "Cost of pinmask depth on the NIR camera (5.86 um pixels, 1920 x 1200, 34 px per cell, "
        "544 px period; photons 20, read noise 6 e-, NSR tuned, Wiener + TV) beside a forward + "
        "inverse FFT of the sensor's size, timed in the same run.");
    cmd->footer(
        "The depth run is timed once; the FFT pair is the minimum over --repeat runs. Threads: "
        "the hardware threads, as pinmask depth.\nExample: pinmask bench depth --distances 9");
    cmd->add_option("--distances", opts->bench.distances,
                    "Object distances from 0.9 m to 2 m, equally spaced in 1/u (2..100)")
        ->capture_default_str();
    cmd->add_option("--rows", opts->bench.rows, "FFT reference rows (64..8192)")
        ->capture_default_str();
    cmd->add_option("--cols", opts->bench.cols, "FFT reference columns (64..8192)")
        ->capture_default_str();
    cmd->add_option("--repeat", opts->bench.repeat, "Runs of the FFT pair (>= 1)")
        ->capture_default_str();
    cmd->add_flag("--no-tv", opts->no_tv, "Wiener only (as depth --no-tv)");
    cmd->add_flag("--json", opts->json, "One JSON object on stdout");
    cmd->callback([opts] { run(*opts); });
}

}  // namespace pinmask::cli
