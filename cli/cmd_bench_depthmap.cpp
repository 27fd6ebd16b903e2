// `pinmask bench depthmap`: the cost of `pinmask depthmap` on a 512 x 512 capture over 16 planes
// beside an FFT pair of that size, timed in the same run (bench/depthmap_bench.hpp).
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/depthmap_bench.hpp"
#include "cli/commands.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    DepthmapBenchOptions bench;
    bool json = false;
};

void run(const Options& o) {
    if (!o.json) {
        std::fprintf(stderr,
                     "running depthmap %d x %d over %d planes, %d time(s), then the FFT "
                     "pair...\n",
                     o.bench.size, o.bench.size, o.bench.planes, o.bench.repeat);
    }
    const DepthmapBenchResult r = bench_depthmap(o.bench);
    const double ratio = r.depthmap_seconds / r.fft_pair_seconds;
    if (o.json) {
        std::cout << nlohmann::json{{"size", o.bench.size},
                                    {"planes", o.bench.planes},
                                    {"depthmap_seconds", r.depthmap_seconds},
                                    {"depthmap_cpu_seconds", r.depthmap_cpu_seconds},
                                    {"fft_pair_seconds", r.fft_pair_seconds},
                                    {"fft_pair_cpu_seconds", r.fft_pair_cpu_seconds},
                                    {"depthmap_over_fft_pair", ratio},
                                    {"capture_depth_m", r.capture_depth_m}}
                         .dump()
                  << "\n";
        return;
    }
    std::printf("machine-vision camera, %d x %d capture (scene at 0.7 m), %d planes 0.4-2 m\n",
                o.bench.size, o.bench.size, o.bench.planes);
    std::printf("  depthmap                    %9.3f s wall  %9.3f s CPU\n", r.depthmap_seconds,
                r.depthmap_cpu_seconds);
    std::printf(
        "  FFT pair %4d x %-4d         %9.3g s wall  %9.3g s CPU   depthmap / FFT pair = %.0f\n",
        o.bench.size, o.bench.size, r.fft_pair_seconds, r.fft_pair_cpu_seconds, ratio);
    std::printf("  (whole-capture depth %.3f m)\n", r.capture_depth_m);
}

}  // namespace

void add_bench_depthmap(CLI::App& bench) {
    auto opts = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "depthmap",
        "Cost of pinmask depthmap on a 512 x 512 capture over 16 planes (machine-vision camera, "
        "0.4-2 m) beside a forward + inverse FFT of the capture's size, timed in the same run.");
    cmd->footer(
        "Both figures are the minimum over --repeat runs (FFT pair: FFTW_MEASURE plans).\n"
        "Example: pinmask bench depthmap --repeat 3");
    cmd->add_option("--size", opts->bench.size, "Capture side, px (64..4096)")
        ->capture_default_str();
    cmd->add_option("--planes", opts->bench.planes, "Planes of the sweep (2..100)")
        ->capture_default_str();
    cmd->add_option("--repeat", opts->bench.repeat, "Runs of each (>= 1)")->capture_default_str();
    cmd->add_flag("--json", opts->json, "One JSON object on stdout");
    cmd->callback([opts] { run(*opts); });
}

}  // namespace pinmask::cli
