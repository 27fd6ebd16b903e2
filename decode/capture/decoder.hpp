// Decoding one channel of a capture with a known PSF: the facade over the algorithms of decode/
// (one concept per file: wiener, tikhonov, tv_l2, tvqc, richardson_lucy, convolution models).
//
// Notation for decode/: p the capture (one period for the cyclic model, the sensor window for the
// linear model), a the PSF, x the scene estimate, A x = a (*) x the forward operator, N = number
// of pixels of x. deconvwnr parity: the PSF is zero-padded to the working size and circularly
// shifted so its central element (0-based index floor(size/2) per axis) lands at the origin.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "decode/solvers/auto_weight.hpp"

namespace pinmask {

class DecodePlanCache;      // decode/solvers/plan_cache.hpp
class ConvolutionOperator;  // decode/solvers/convolution.hpp
class WienerFilter;         // decode/solvers/wiener.hpp

enum class DecodeMethod { kWiener, kTikhonov, kTv, kTvqc, kRichardsonLucy };

// cyclic: circular convolution over one period (the paper; x has the capture's size).
// linear: zero-padded linear convolution followed by a crop to the capture's size (non-cyclic
//         masks and ordinary lensless captures; x lives on the padded grid and is cropped back).
enum class ConvModel { kCyclic, kLinear };

enum class TikhonovRegulariser { kIdentity, kGradient };

// One row of an iterative solver's record, for error-against-run-time plots.
struct IterationRecord {
    int iteration = 0;
    double seconds = 0.0;    // since the solver started
    double objective = 0.0;  // the method's own objective (see each solver)
    double residual = 0.0;   // ||A x - p||_2 (TVQC: relative to eps; see tvqc.hpp)
};

// Options shared by the iterative methods (tv, tvqc, richardson-lucy); closed-form methods
// read none of them (warm_start excepted: it is checked for size with every method).
struct IterativeParams {
    int max_iterations = 200;
    double tolerance = 1e-4;          // relative change of x between iterations
    std::optional<Plane> warm_start;  // initial x (working size)
    bool record_history = true;
    const std::atomic<bool>* stop = nullptr;            // see IterativeOptions::stop
    std::atomic<long long>* iterations_done = nullptr;  // see IterativeOptions::iterations_done
    // InvalidInput naming the field ("iterative.max_iterations", ...), its value and the rule.
    void validate() const;
};

struct WienerParams {
    double nsr = 0.01;  // scalar noise-to-signal power ratio (>= 0)
    // Chooses nsr from the capture (decode/solvers/auto_weight.hpp) in place of the value above.
    bool automatic = false;
    std::optional<Plane> nsr_per_frequency;  // per-frequency NSR (working size), replaces nsr
    void validate() const;
};

struct TikhonovParams {
    double lambda = 1e-3;    // >= 0 (0: the unregularised inverse filter)
    bool automatic = false;  // chooses lambda from the capture (decode/solvers/auto_weight.hpp)
    TikhonovRegulariser regulariser = TikhonovRegulariser::kIdentity;
    void validate() const;
};

struct TvParams {
    double lambda = 1e-3;    // >= 0, capture units
    bool automatic = false;  // chooses lambda from the capture (decode/solvers/auto_weight.hpp)
    bool nonnegative = false;
    void validate() const;
};

struct TvqcParams {
    std::optional<double> eps;          // ||A x - p||_2 <= eps
    std::optional<double> noise_sigma;  // eps from the noise level when eps is unset
    bool nonnegative = false;
    // Also refuses neither eps nor noise_sigma, and both at once.
    void validate() const;
};

// The method, the convolution model, the options every iterative method shares and one struct
// per method: a method reads its own struct only (richardson-lucy has no parameters beyond the
// shared iterative ones), so a parameter is never shared by accident between two methods.
struct DecodeOptions {
    DecodeMethod method = DecodeMethod::kWiener;
    ConvModel model = ConvModel::kCyclic;
    // Every method: transforms and iterates in float32 (FFTW float); set-up, sums and the
    // reported residual and objective stay in double. Tolerances: tests/decode/test_precision.cpp.
    bool single_precision = false;
    IterativeParams iterative;
    WienerParams wiener;
    TikhonovParams tikhonov;
    TvParams tv;
    TvqcParams tvqc;
    // The capture's per-pixel noise sigma (capture units) for the automatic weights and tv's
    // weight warning, when it is known better than from the decoded plane (the capture pipeline
    // measures it before downsampling, where the scene reaches the finest scale least); unset:
    // estimated from the plane (decode/solvers/noise_estimate.hpp).
    std::optional<double> auto_noise_sigma;
    // Optional: operators and closed-form filters made once and reused across calls with the same
    // PSF and grid (decode/solvers/plan_cache.hpp; batch decode). Not owned; results are the same
    // bytes.
    DecodePlanCache* plans = nullptr;
    // The method must be one of kDecodeMethods (an unknown value is an error, never a fall-through
    // to any method); then the chosen method's struct (and `iterative` for an iterative method).
    // InvalidInput naming the field, its value and the rule.
    void validate() const;
};

struct DecodeResult {
    Plane image;                           // the estimate, same size as the capture
    std::vector<IterationRecord> history;  // empty for closed-form methods
    int iterations = 0;
    double objective = 0.0;
    double residual = 0.0;
    bool converged = true;
    bool constraint_met = true;  // tvqc: ||A x - p||_2 <= eps at exit (to kTvqcFeasibilityTol)
    bool interrupted = false;    // ended early by IterativeOptions::stop (DecodeOptions::stop)
    // An automatic weight: the weight chosen, the noise sigma it used (capture units) and the
    // fitted scene spectrum's exponent; unset for a weight the caller gave.
    std::optional<AutoWeight> auto_weight;
    // One line each, field references in backquotes (core/errors/field_names.hpp): a method the
    // input makes poor (see decode_plane). The faces show them (CLI stderr, Python warnings.warn).
    std::vector<std::string> warnings;
    double seconds = 0.0;
};

// Decodes one channel. Throws InvalidInput for non-finite inputs, a PSF with zero or negative
// sum, a PSF larger than the working size, or options out of range (naming the option).
// Per method (x on the working grid, see decode/solvers/convolution.hpp; residual = ||A x - p||_2):
//   wiener    decode/solvers/wiener.hpp (deconvwnr); objective ||A x - p||^2 + nsr ||x||^2
//   tikhonov  decode/solvers/tikhonov.hpp; objective ||A x - p||^2 + lambda ||L x||^2
//   tv        decode/solvers/tv_l2.hpp (ADMM); objective 1/2 ||A x - p||^2 + lambda TV(x)
//   tvqc      decode/solvers/tvqc.hpp; eps = options.eps, else tvqc_eps_from_sigma(noise_sigma, N);
//             objective TV(x)
//   rl        decode/solvers/richardson_lucy.hpp; objective the I-divergence
// Linear model: wiener and tikhonov filter the zero-padded capture on the padded grid (an
// approximation that ignores the crop); the iterative methods solve the exact linear model.
// Scale: every method is solved for p / s (s = max |p|, with lambda (tv), eps and noise_sigma
// (tvqc) and the warm start divided by s) and the estimate multiplied back, so a capture of any
// magnitude (1e-300 .. 1e300) meets the same numbers inside the solvers; image, residual,
// objective and history are reported in the capture's units (an objective quadratic in p is +inf
// beyond |p| ~ 1e154: it left the double range).
// Automatic weight (wiener.automatic, tikhonov.automatic): choose_closed_form_weight on the
// capture, the operator's OTF and the regulariser's symbol, then the decode with that weight;
// tv.automatic: choose_tv_weight. Either is recorded in DecodeResult::auto_weight.
// Warnings (DecodeResult::warnings): tv with a given lambda more than 10 times from the
// automatic one either way; wiener or tikhonov on the linear model with a capture that fills
// the frame (its border band, 1/16 of the smaller side wide, averages at least half the
// capture's mean magnitude): the filter reads the light beyond the sensor as zero.
// Result check: an estimate or residual that is not finite (or a NaN objective) throws
// RuntimeFailure naming the method (never a NaN/Inf image returned as a success).
DecodeResult decode_plane(const Plane& capture, const Plane& psf, const DecodeOptions& options);

// The filter of a closed-form method (wiener with a scalar or per-frequency NSR, tikhonov) from
// the operator's OTF, exactly as decode_plane builds it (the plan cache builds it here too).
WienerFilter closed_form_filter(const ConvolutionOperator& op, const DecodeOptions& o);

}  // namespace pinmask
