// `pinmask bench calibrate`: calibrate's time on a full-sensor point-source capture beside one
// FFTW transform pair of the same size.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/calibrate_bench.hpp"
#include "cli/commands.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    CalibrateBenchOptions bench;
    bool json = false;
};

void run(const Options& o) {
    if (!o.json) std::fprintf(stderr, "rendering and timing (%d runs)...\n", o.bench.repeat);
    const CalibrateBenchResult r = bench_calibrate(o.bench);
    const double ratio = r.calibrate_seconds / r.fft_pair_seconds;
    if (o.json) {
        std::cout << nlohmann::json{{"rows", r.rows},
                                    {"cols", r.cols},
                                    {"pinholes_fitted", r.pinholes_fitted},
                                    {"iterations", r.iterations},
                                    {"calibrate_seconds", r.calibrate_seconds},
                                    {"fft_pair_seconds", r.fft_pair_seconds},
                                    {"calibrate_over_fft_pair", ratio},
                                    {"rotation_deg", r.rotation_deg},
                                    {"rotation_sigma_deg", r.rotation_sigma_deg},
                                    {"true_rotation_deg", r.true_rotation_deg},
                                    {"pitch_x_px", r.pitch_x_px},
                                    {"true_pitch_px", r.true_pitch_px}}
                         .dump()
                  << "\n";
        return;
    }
    std::printf(
        "point-source capture %d x %d px (NIR camera, 34 px per cell), %d pinholes fitted, "
        "%d iterations\n",
        r.cols, r.rows, r.pinholes_fitted, r.iterations);
    std::printf("  calibrate                %10.4g s   calibrate / FFT pair = %.0f\n",
                r.calibrate_seconds, ratio);
    std::printf("  FFTW pair %4d x %4d     %10.4g s\n", r.cols, r.rows, r.fft_pair_seconds);
    std::printf("  rotation %.5f +- %.5f deg (truth %.5f), pitch %.4f px (truth %.4f)\n",
                r.rotation_deg, r.rotation_sigma_deg, r.true_rotation_deg, r.pitch_x_px,
                r.true_pitch_px);
}

}  // namespace

void add_bench_calibrate(CLI::App& bench) {
    auto opts = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "calibrate",
        "Time of calibrate on a point-source capture of the whole sensor (the NIR camera of "
        "docs/calibration.md: 5.86 um pixels, 34 px per cell, spots one cell wide; a 10 x 10 "
        "mask with 15 pinholes tiled 6 x 6, 1.0 deg, Poisson and read noise) beside one FFTW "
        "forward + inverse pair of the same size, timed in the same run; each figure the "
        "minimum over --repeat runs (the FFT pair over at least 3).");
    cmd->footer("Example: pinmask bench calibrate --rows 1200 --cols 1920");
    cmd->add_option("--rows", opts->bench.rows, "Sensor rows (400..4096)")->capture_default_str();
    cmd->add_option("--cols", opts->bench.cols, "Sensor columns (400..4096)")
        ->capture_default_str();
    cmd->add_option("--repeat", opts->bench.repeat, "Runs of calibrate (>= 1)")
        ->capture_default_str();
    cmd->add_flag("--json", opts->json, "One JSON object on stdout");
    cmd->callback([opts] { run(*opts); });
}

}  // namespace pinmask::cli
