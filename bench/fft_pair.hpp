// The same-run reference of the benchmarks that time a whole command (depth, calibrate): the
// bare FFTW r2c + c2r pair of a frame's size in double, planned with FFTW_MEASURE (the planner
// times candidates: the fastest pair FFTW offers on this machine, whatever the process's own
// planner is set to), best of `repeat` runs.
#pragma once

namespace pinmask {

struct FftPairTime {
    double wall_seconds = 0.0;
    double cpu_seconds = 0.0;  // process CPU time (all threads)
};

FftPairTime measured_fft_pair(int rows, int cols, int repeat, int threads);

}  // namespace pinmask
