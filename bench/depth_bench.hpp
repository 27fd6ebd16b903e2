// Cost of `pinmask depth` on a full-size sensor beside an FFT pair of the sensor's size (bare
// FFTW, FFTW_MEASURE: bench/fft_pair), timed in the same run (so the ratio, not the seconds, is
// the figure to compare between machines and loads).
//
// The camera: the NIR camera of the benchmarks page (5.86 um pixels, 1920 x 1200 sensor, f' =
// 75 mm, sensor 45 mm behind the lens, u = 1.2 m, 850 nm, d = 455.406 um: the pinhole solved
// for 34 px per cell at u, on the 1 nm grid), a seeded 16 x 16 pattern of K = 20 pinholes at
// least 2 cells apart on the torus, 2 x 2 tiles: a 544 px period.
// The run: depth_analysis (optimize/metrics/depth_loss.hpp) at `distances` object distances from
// 0.9 m to 2 m equally spaced in 1/u, letter-R and natural, the photon model at 20 electrons per
// pixel per pinhole with 6 e- read noise, Wiener NSR tuned, with TV-L2. Figures: the depth run
// (once: it takes seconds), and the forward + inverse real FFT of the rows x cols sensor (the
// minimum over `repeat` runs), wall clock and process CPU time.
#pragma once

namespace pinmask {

struct DepthBenchOptions {
    int distances = 9;  // 2..100
    int rows = 1200;    // the FFT reference's size, 64..8192
    int cols = 1920;
    int repeat = 5;   // runs of the FFT pair, >= 1
    int threads = 1;  // depth_analysis's worker threads, 1..256
    bool with_tv = true;
};

struct DepthBenchResult {
    int period_px = 0;
    int distances = 0;
    double depth_seconds = 0;      // wall clock
    double depth_cpu_seconds = 0;  // process CPU time, all threads
    double fft_pair_seconds = 0;   // wall clock, minimum over repeat
    double fft_pair_cpu_seconds = 0;
    double worst_wiener_loss_db = 0;  // the largest Wiener loss of the run (a sanity figure)
};

// Throws InvalidInput for options out of range, naming the field.
DepthBenchResult bench_depth(const DepthBenchOptions& options);

}  // namespace pinmask
