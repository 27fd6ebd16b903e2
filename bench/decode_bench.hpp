// Decoder speed: each method's time per call on an R x C channel, beside bare FFTW r2c + c2r
// pairs of the same size planned with FFTW_MEASURE on FFTW's own buffers (double and float),
// timed in the same run, as ratios to each (the best reference the library can be held to).
//
// Methods (cyclic model, a seeded coded-aperture PSF of 20 square pinholes and a seeded scene):
//   wiener            WienerFilter::apply with the filter precomputed (one r2c, a complex
//                     multiply, one c2r)
//   wiener_single     WienerFilter::apply_single (the same in float32, conversions included)
//   tv_l2_iteration_single  one TV-L2 iteration in float32
//   tv_l2_to_0.2dB    the "paper problem" (a 16 x 16 pattern of K = 20 pinholes, 8 px cells, box
//                     kernel; the seeded scene; Gaussian noise at 30 dB SNR; lambda 1e-3 of the
//                     scene's unit peak): the iterations after which the PSNR against the true
//                     scene stays within 0.2 dB of the converged PSNR (5000 iterations, tol 1e-9),
//                     and the time of a run of that many iterations. Only for sizes 16 n_px.
//   tikhonov          the gradient-regularised Tikhonov filter, precomputed, applied
//   tv_l2_iteration   one ADMM iteration of solve_tv_l2: (time of 1 + m iterations - time of 1) / m
//   tvqc_to_tolerance a whole solve_tvqc run at tolerance 1e-4 (eps from the noise level), capped
//                     at tvqc_max_iterations, timed once; its iteration count is reported
//   tvqc_iteration    one TVQC iteration, measured like tv_l2_iteration (the first 1 + m include
//                     the step balance's adaptation)
//   tvqc_iteration_single, rl_iteration_single  the same in float32
//   rl_iteration      one Richardson-Lucy iteration, measured like tv_l2_iteration
// Linear model (options.linear, on by default): the same shape is the padded working grid of a
// capture of about half its size per axis with a PSF of the other half (600 x 800: a 300 x 400
// capture and a 301 x 401 PSF, as the DiffuserCam hand after the tutorial's preprocessing), the
// PSF a seeded caustic-like pattern spread over its whole support, the scene seeded rectangles:
//   tv_l2_linear_iteration_single     one TV-L2 iteration in float32 with x >= 0 (the decode of a
//                                     real capture)
//   tvqc_linear_iteration_single, rl_linear_iteration_single   likewise
// fft_pairs is the floor of each figure: the FFT pairs the method's transforms cost (an
// iteration's, or the call's for the closed forms), so fft_pairs x the float pair is the time an
// iteration would take if everything but FFTW were free.
// Each other figure is the minimum over `repeat` timed batches of the per-call time (batches last
// at least min_batch_seconds): the minimum is the figure least disturbed by other load.
// The default sizes keep a run near 10 s on an idle 2-core machine; 1024 adds ~20 s (TVQC).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pinmask {

struct DecodeBenchOptions {
    std::vector<int> sizes{128, 512};  // N x N channels, each 16..8192
    // Extra R x C shapes (each side 16..8192), e.g. {{480, 720}} for the paper's sensor.
    std::vector<std::pair<int, int>> shapes;
    int repeat = 3;                   // timed batches per figure, >= 1
    double min_batch_seconds = 0.02;  // > 0
    int tvqc_max_iterations = 300;    // >= 1
    std::uint64_t seed = 1;
    // FFTW threads of the library's transforms during the run (core/fft/fft's rule: only sizes from
    // kFftThreadMinPixels up use them) and of the reference pairs of the same size, so both sides
    // run the same thread count. 1 by default: one core, the figure least disturbed by load.
    int threads = 1;  // 1..1024
    // Time the calling thread's CPU time instead of wall time: on a machine shared with other
    // work, time-slicing inflates wall time but not CPU time (caches are still shared). Only
    // meaningful with threads = 1 (FFTW's worker threads are not counted).
    bool cpu_time = false;
    // Also time the linear-model iterations (see above) at each shape.
    bool linear = true;
};

struct DecodeBenchRecord {
    std::string method;
    int size = 0;  // rows (= cols for the N x N sizes)
    int cols = 0;
    double seconds_per_call = 0.0;
    double fft_pair_seconds = 0.0;        // bare FFTW r2c + c2r (FFTW_MEASURE, double), same run
    double ratio = 0.0;                   // seconds_per_call / fft_pair_seconds
    double fft_pair_float_seconds = 0.0;  // the same pair in float (fftwf, FFTW_MEASURE)
    double ratio_float = 0.0;             // seconds_per_call / fft_pair_float_seconds
    int iterations = 0;                   // tvqc_to_tolerance: iterations run; others 1 (or 0)
    bool converged = true;                // tvqc_to_tolerance: tolerance met within the cap
    int fft_pairs = 0;  // the floor: FFT pairs per call (iteration) of the method; 0 = not one
    std::string model = "cyclic";  // "cyclic" or "linear"
};

// TV-L2 iterations to come within `within_db` of the converged PSNR on the paper problem of size
// n (a multiple of 16; see tv_l2_to_0.2dB above). `reached` is false when max_iterations did not.
struct TvConvergence {
    int iterations = 0;
    bool reached = false;
    double converged_psnr_db = 0.0;
    double first_psnr_db = 0.0;
};
TvConvergence tv_l2_iterations_to_converged(int n, double lambda, double snr_db, double within_db,
                                            int max_iterations, std::uint64_t seed);

// Runs every method at every size on the calling thread (sets core/fft/fft's thread count to
// options.threads for the run and restores it). Throws InvalidInput for options out of
// range (naming the field).
std::vector<DecodeBenchRecord> bench_decode(const DecodeBenchOptions& options);

}  // namespace pinmask
