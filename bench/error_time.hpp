// Error against run time of every decoder: for one PSF (one period of a mask), a set of scenes and
// noise levels, each decoder setting is run on the same simulated captures and recorded as
// (seconds, PSNR, SSIM). The curves show what an iteration budget buys.
//
// Captures: optimize/simulate/simulate.hpp, one period, Gaussian noise at each SNR (the seed stream
// of scene s and SNR index k is mixed from options.seed, s and k), so every decoder sees the same
// noisy capture. Decoders (decode/capture/decoder.hpp, cyclic model):
//   wiener            at each NSR of options.wiener_nsr (closed form)
//   tikhonov          gradient regulariser at each lambda of options.tikhonov_lambda (closed form)
//   tv-l2             ADMM at options.tv_lambda, stopped after exactly k iterations for each k of
//                     options.iterations (tolerance 0)
//   tvqc              eps from the true noise sigma (tvqc.hpp's l1-magic rule), k iterations
//   richardson-lucy   k iterations
// The iterative solvers keep internal state (duals, penalties, step balance) that a warm start
// does not restore, so each count is a separate run from the solver's own starting point: the
// iterate after k iterations of one long run is exactly what is measured.
// Timing: seconds of decode_plane (filter or operator set-up included) on the calling thread, per
// channel summed, as the thread's CPU time (CLOCK_THREAD_CPUTIME_ID): the decoders and FFTW run
// single-threaded, so on an idle machine this equals the wall time, and on a loaded one it does
// not count the time other processes hold the core. Wall time is recorded beside it. After one
// untimed warm-up decode per closed-form setting and per iterative solver at 1 iteration (FFTW
// plans are made once per process, not per decode). A point whose first run is shorter than
// options.repeat_below_seconds is run options.repeats times and the median is recorded. Quality:
// PSNR and SSIM (optimize/simulate/image_quality.hpp) of the estimate against the scene.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "optimize/metrics/simulated_metrics.hpp"

namespace pinmask {

struct ErrorTimeOptions {
    std::vector<double> snr_db{30.0};
    std::vector<int> iterations{1, 3, 10, 30, 100, 300, 1000};                 // each >= 1
    std::vector<double> wiener_nsr{1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1};  // each >= 0
    std::vector<double> tikhonov_lambda{1e-4, 3e-4, 1e-3, 3e-3, 1e-2};         // each >= 0
    double tv_lambda = 1e-3;                                                   // > 0
    int repeats = 5;                     // timing repeats of fast points (median), >= 1
    double repeat_below_seconds = 0.25;  // a first run shorter than this is repeated, >= 0
    std::uint64_t seed = 1;
    // Called before each decoder setting with a short description (progress); may be empty.
    std::function<void(const std::string&)> progress;

    // Throws InvalidInput naming the field, value and rule.
    void validate() const;
};

// One decoder setting on one scene at one SNR.
struct ErrorTimeRecord {
    double snr_db = 0.0;
    std::string scene;
    std::string decoder;        // wiener | tikhonov | tv-l2 | tvqc | richardson-lucy
    std::string parameter;      // nsr | lambda | eps (the setting's name)
    double value = 0.0;         // its value (tvqc: eps of channel 0)
    int iterations = 0;         // requested; 0 for the closed forms
    int iterations_run = 0;     // what the solver ran (max over channels)
    bool converged = true;      // solver's own flag (all channels)
    double seconds = 0.0;       // median CPU time of the decode (all channels)
    double wall_seconds = 0.0;  // median wall-clock time of the same runs
    int timing_runs = 1;        // runs behind the median
    double psnr_db = 0.0;
    double ssim = 0.0;  // NaN when the period is below the 11 x 11 SSIM window
};

// Runs the sweep. psf: m x m, finite, sum > 0; every scene m x m (1 or 3 channels, values in
// [0, 1]); at least one scene. Records ordered by SNR, scene, decoder, setting.
std::vector<ErrorTimeRecord> run_error_time(const Plane& psf, const std::vector<NamedScene>& scenes,
                                            const ErrorTimeOptions& options);

// A curve point averaged over scenes: mean PSNR, mean SSIM, mean seconds of one decoder setting
// at one SNR. `scenes` counts the records averaged.
struct ErrorTimePoint {
    double snr_db = 0.0;
    std::string decoder;
    std::string parameter;
    double value = 0.0;  // tvqc: mean eps
    int iterations = 0;
    double seconds = 0.0;  // CPU time
    double wall_seconds = 0.0;
    double psnr_db = 0.0;
    double ssim = 0.0;
    int scenes = 0;
};

// Mean over scenes of the records with equal (snr, decoder, parameter, iterations, and value for
// the closed forms), in first-appearance order.
std::vector<ErrorTimePoint> mean_over_scenes(const std::vector<ErrorTimeRecord>& records);

// Per (SNR, decoder): the point of highest PSNR (ties: the faster), and the fastest point within
// tol_db of it (for an iterative decoder: the iteration budget that already gets there; for a
// closed form: the best point itself, its settings being no time budget). First-appearance order.
struct DecoderSummary {
    ErrorTimePoint best;
    ErrorTimePoint near_best;
};
std::vector<DecoderSummary> summarise_decoders(const std::vector<ErrorTimePoint>& points,
                                               double tol_db);

// The tolerance of the "near best" column of the report: 0.1 dB, below the scatter of PSNR
// between scenes and noise draws.
inline constexpr double kNearBestDb = 0.1;

// The paper's two reference timings of its decodes (Wiener, TVQC), marked on the plot.
inline constexpr double kPaperWienerSeconds = 0.004;
inline constexpr double kPaperTvqcSeconds = 7.2;

}  // namespace pinmask
