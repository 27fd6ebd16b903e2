// Cost of the decoder's period check (decode/capture/period.hpp) beside a Wiener decode of the same
// capture, timed in the same run (the check is meant to cost at most 10 % of the decode).
// "A Wiener decode of the same capture" is reported both ways: the whole frame (crop none) and
// the centred period (decode's default); the second is the bar the check is held to.
//
// The capture: a machine-vision camera (3.45 um pixels, 25 mm lens, sensor 20 mm behind, u = 2 m,
// 530 nm, d = 345 um: 21 px per cell, a 336 px period) simulated over a rows x cols sensor
// (default its 2048 x 2448) from a seeded 16 x 16, K = 20 pattern and the letter-R scene, 30 dB.
// Figures (each the minimum over `repeat` runs):
//   check_seconds         check_period of the whole frame against the 336 px PSF (the
//                         early exit at the PSF's period on strips of the frame,
//                         decode/capture/period.hpp; the full search only if it doubts)
//   wiener_frame_seconds  decode_plane (Wiener, cyclic) of the whole frame, PSF zero-padded
//   wiener_period_seconds decode_plane of the centred period only (what decode does by default)
//   doubted_check_seconds check_period of a capture the early exit doubts: the same camera and
//                         mask with the natural scene at 10 dB (a repeat at the noise), which
//                         takes the full search over every line in both views
//                         (decode/capture/period.hpp); held beside the same two decodes of that
//                         capture's size
// Each check also reports whether the early exit decided both axes.
#pragma once

namespace pinmask {

struct PeriodBenchOptions {
    int rows = 2048;  // sensor window, each >= 2 periods (672) and <= 8192
    int cols = 2448;
    int repeat = 3;  // >= 1
};

struct PeriodBenchResult {
    int rows = 0, cols = 0, period_px = 0;
    double check_seconds = 0;
    double wiener_frame_seconds = 0;
    double wiener_period_seconds = 0;
    bool check_matches = false;     // the check agreed with the PSF (no false warning)
    bool check_early_exit = false;  // both axes decided by the early exit
    double doubted_check_seconds = 0;
    bool doubted_matches = false;
    bool doubted_early_exit = false;
};

// Throws InvalidInput for options out of range, naming the field.
PeriodBenchResult bench_period(const PeriodBenchOptions& options);

}  // namespace pinmask
