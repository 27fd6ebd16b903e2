// Time of `calibrate` on a full-sensor point-source capture beside one FFTW transform pair of the
// same size (bare FFTW, FFTW_MEASURE, one thread: bench/fft_pair), timed in the same run (the bar:
// <= 2 s on one core for 1920 x 1200).
//
// The capture: the NIR camera of the calibration docs (5.86 um pixels, lens 75 mm, sensor 45 mm
// behind it, u = 1.2 m, 850 nm, a 455.4 um pinhole: 34 px per cell, Fresnel number 0.59 with the
// lens, spots one cell wide), a seeded random 10 x 10 mask with 15 pinholes tiled 6 x 6, rotated
// 1.0 deg with the pitch +0.5 %, centred on a rows x cols sensor (default 1920 x 1200). It is
// rendered with calibrate's own forward model (decode/calibrate/forward_fit's fitted_psf: a timing
// input, not a test of the fit; the tests render with independent models), 5e5 counts per
// pinhole, a background of 20, Poisson photons and 3 counts of read noise, seeded.
// Figures (each the minimum over `repeat` runs): calibrate_point_source without a dark frame
// (the whole pipeline: spots, FFT start, fit, PSFs, kernel), and Fft2 forward + inverse of one
// rows x cols plane. The fitted rotation and pitch are reported beside the truth.
#pragma once

namespace pinmask {

struct CalibrateBenchOptions {
    int rows = 1200;  // sensor window, each 400..4096
    int cols = 1920;
    int repeat = 1;  // >= 1
};

struct CalibrateBenchResult {
    int rows = 0, cols = 0, pinholes_fitted = 0, iterations = 0;
    double calibrate_seconds = 0, fft_pair_seconds = 0;
    double rotation_deg = 0, rotation_sigma_deg = 0, true_rotation_deg = 0;
    double pitch_x_px = 0, true_pitch_px = 0;
};

// Throws InvalidInput for options out of range, naming the field.
CalibrateBenchResult bench_calibrate(const CalibrateBenchOptions& options);

}  // namespace pinmask
