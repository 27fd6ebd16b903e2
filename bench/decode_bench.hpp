// Decoder speed: each method's time per call on an N x N channel, beside a bare FFTW r2c + c2r
// pair of the same size timed in the same run, as a ratio (machine-independent-ish).
//
// Methods (cyclic model, a seeded coded-aperture PSF of 20 square pinholes and a seeded scene):
//   wiener            WienerFilter::apply with the filter precomputed (one r2c, a complex
//                     multiply, one c2r)
//   tikhonov          the gradient-regularised Tikhonov filter, precomputed, applied
//   tv_l2_iteration   one ADMM iteration of solve_tv_l2: (time of 1 + m iterations - time of 1) / m
//   tvqc_to_tolerance a whole solve_tvqc run at tolerance 1e-4 (eps from the noise level), capped
//                     at tvqc_max_iterations, timed once; its iteration count is reported
//   rl_iteration      one Richardson-Lucy iteration, measured like tv_l2_iteration
// Each other figure is the minimum over `repeat` timed batches of the per-call time (batches last
// at least min_batch_seconds): the minimum is the figure least disturbed by other load.
// The default sizes keep a run near 10 s on an idle 2-core machine; 1024 adds ~20 s (TVQC).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pinmask {

struct DecodeBenchOptions {
    std::vector<int> sizes{128, 512};  // N, each 16..8192
    int repeat = 3;                    // timed batches per figure, >= 1
    double min_batch_seconds = 0.02;   // > 0
    int tvqc_max_iterations = 300;     // >= 1
    std::uint64_t seed = 1;
};

struct DecodeBenchRecord {
    std::string method;
    int size = 0;
    double seconds_per_call = 0.0;
    double fft_pair_seconds = 0.0;  // bare FFTW r2c + c2r, same size, same run
    double ratio = 0.0;             // seconds_per_call / fft_pair_seconds
    int iterations = 0;             // tvqc_to_tolerance: iterations run; others 1 (or 0)
    bool converged = true;          // tvqc_to_tolerance: tolerance met within the cap
};

// Runs every method at every size on the calling thread. Throws InvalidInput for options out of
// range (naming the field).
std::vector<DecodeBenchRecord> bench_decode(const DecodeBenchOptions& options);

}  // namespace pinmask
