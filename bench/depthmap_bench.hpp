// Cost of `pinmask depthmap` on a 512 x 512 capture over 16 planes beside an FFT pair of that
// size (bare FFTW, FFTW_MEASURE: bench/fft_pair), timed in the same run (the ratio, not the
// seconds, is the figure to compare between machines and loads).
//
// The camera: the close-range machine-vision camera of docs/depth.md (3.45 um pixels, f' = 25 mm,
// sensor 20 mm behind the lens, 530 nm, d = 115 um), a seeded 16 x 16 pattern of K = 20 pinholes
// at least 2 cells apart on the torus, 2 x 2 tiles. The capture: a seeded random scene (uniform
// values) circularly convolved with the exact-geometry PSF at 0.7 m (the content does not change
// the work). The run: depthmap (decode/depthmap/depthmap.hpp) over 16 planes from 0.4 m to 2 m, the
// command's defaults (NSR 0.01, window 121 px, smoothing weight 8: semi-global labelling along 8
// paths), best of `repeat` runs.
#pragma once

namespace pinmask {

struct DepthmapBenchOptions {
    int size = 512;   // capture side, 64..4096
    int planes = 16;  // 2..100
    int repeat = 3;   // runs of each, >= 1
};

struct DepthmapBenchResult {
    double depthmap_seconds = 0;  // wall clock, minimum over repeat
    double depthmap_cpu_seconds = 0;
    double fft_pair_seconds = 0;  // wall clock, minimum over repeat
    double fft_pair_cpu_seconds = 0;
    double capture_depth_m = 0;  // the whole-capture estimate (a sanity figure: about 0.7 m)
};

// Throws InvalidInput for options out of range, naming the field.
DepthmapBenchResult bench_depthmap(const DepthmapBenchOptions& options);

}  // namespace pinmask
