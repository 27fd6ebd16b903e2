// TV-L2 deconvolution: x = argmin 1/2 ||A x - p||_2^2 + lambda TV(x) [+ indicator(x >= 0)],
// isotropic TV with periodic differences (decode/solvers/gradient.hpp), A a convolution model
// (decode/solvers/convolution.hpp), by ADMM.
//
// Splits (scaled duals u, v, eta; penalties rho for z and w, rho_s for s):
//   z = grad x,  w = x (only with nonnegative),  s = H x (only for the linear model).
// x-step, diagonal in Fourier space:
//   cyclic: (|H|^2 + rho |D|^2 + rho_w) X = conj(H) P + rho F[grad^T (z - u)] + rho_w F[w - v]
//   linear: (rho_s |H|^2 + rho |D|^2 + rho_w) X = rho_s conj(H) F[s - eta] + (same terms)
//   with |D|^2 = 4 sin^2(pi k / R) + 4 sin^2(pi l / C) and rho_w = rho when nonnegative, else 0.
// z-step: isotropic shrinkage of grad x + u by lambda / rho; w-step: max(0, x + v);
// s-step (pointwise): s = (C^T p + rho_s (H x + eta)) / (C^T C 1 + rho_s). Outside the capture
// window C^T C = 0, so there s = H x + eta and eta stays 0: the solver holds q = s - eta on the
// working grid (the next x-step's transform input, written by the s-step itself) and eta on the
// capture window only.
// Over-relaxation alpha = 1.95 (cyclic model without nonnegative), else 1.8: the z-, w- and
// s-steps see alpha (grad x, x, H x) + (1 - alpha) (previous z, w, s) instead of the new values.
// Penalties: rho starts at the mean of |H|^2 over the spectrum unless given, rho_s (rho_crop)
// at the same value (the data term's own weight 1 converged far slower on simulated full-frame
// captures: 3 against 18 dB after 30 iterations, see tv_l2.cpp), and both follow residual
// balancing (x2 / /2 when one residual exceeds 2x the other) every 3
// iterations up to iteration 100, then stay fixed (ADMM convergence holds for the tail).
// Start (no warm start; TvL2Options::start): the quadratic estimate x0 = IFFT[conj(H) P / (|H|^2
// + rho |D|^2)] (one inverse FFT; the linear model's on the zero-padded capture, weights as in
// its x-step), the default for the cyclic model, or 0, the linear model's default; then z =
// shrink(grad x0, lambda / rho), u = grad x0 - z, as after a z-step.
// Scale: solved for p / max|p| with lambda / max|p| and scaled back (decode/capture/decoder.hpp).
// Precision: single_precision runs the iteration in float32 (FFTW float), the pointwise steps in
// float too; the residual, TV and change sums in double.
// Loops (cyclic, per iteration): the spectral solve, and one fused pass over the rows that does
// the z-step, the w-step and the next x-step's right-hand side rho grad^T (z - u) [+ rho (w - v)]
// for the row above (row 0's at the end), branch-free so the compiler vectorises the rows; the
// residual sums are gathered only on the adaptation iterations (every 3rd), vectorised too (the
// row's old z kept in a scratch row, the per-pixel squares summed in four fixed partial sums),
// the TV sum only with records; the pass and the cyclic spectral solve are also built
// for AVX2, chosen at run time (same bits, see set_tv_l2_avx2 below). The relative change of x
// is summed in the same pass when tolerance > 0 (a comparison for tolerance 0). When residual
// balancing changes rho, the right-hand side is rebuilt in a separate pass. Every buffer is
// allocated before the first iteration.
// Loops (linear, per iteration): the spectral solve X = (F[rhs] + rho_s conj(H) Q) / denominator
// and H X in one pass (complex products written out so it vectorises), the s-step in one pass in
// the working precision (the window's formula on the capture window, the relaxation elsewhere,
// its residual sums only on adaptation iterations), and the fused pass as above; each also
// built for AVX2.
// The estimate returned is x, or w (exactly >= 0) when nonnegative. Records: objective
// 1/2 ||A x - p||_2^2 + lambda TV(x) and residual ||A x - p||_2 of the ADMM iterate x (no extra
// FFT); without nonnegative that is the estimate returned, with it x -> w as ADMM converges.
// Cost per iteration: one FFT pair (cyclic; plus one inverse when recording), two pairs (linear:
// F[rhs] and F[q] forward, x and H x inverse; the crop/TV/non-negativity ADMM written with the
// x-step's right-hand side in the spatial domain, as LenslessPiCam does, takes three).
#pragma once

#include <functional>

#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/solver_common.hpp"

namespace pinmask {

// The starting point without a warm start: kAuto is the quadratic start (below) for the cyclic
// model and 0 for the linear model.
enum class TvStart { kAuto, kZero, kQuadratic };

struct TvL2Options : IterativeOptions {
    double lambda = 1e-3;  // >= 0
    bool nonnegative = false;
    double rho = 0.0;  // initial ADMM penalty (> 0), or 0 for the automatic choice
    // Initial penalty of the crop split s = H x (linear model; > 0), or 0 for the automatic choice
    // (see the header comment).
    double rho_crop = 0.0;
    TvStart start = TvStart::kAuto;
    bool single_precision = false;  // iterate in float32 (FFTW float); see the header comment
    // When set, called after every iteration k with the estimate the solver would return had it
    // stopped there (working grid, capture units; x, or w with nonnegative). For measurements of
    // quality against iterations in one run (bench/); costs a conversion per iteration.
    std::function<void(int, const Plane&)> observe;
};

// Runs ADMM; result.image is x on the operator's working grid (crop it with crop_to_capture).
// Throws InvalidInput for a capture of the wrong size or options out of range.
DecodeResult solve_tv_l2(const ConvolutionOperator& op, const Plane& capture,
                         const TvL2Options& options, const Plane* warm_start = nullptr);

// The fused pointwise pass also has an AVX2 build, used when the CPU has AVX2: the same IEEE
// operations per pixel in the same order, so the same bits as the baseline (SSE2) build.
// set_tv_l2_avx2(false) forces the baseline process-wide (tests compare the two); true selects
// AVX2 again when available.
bool tv_l2_avx2_available();
void set_tv_l2_avx2(bool enabled);

// 1/2 ||A x - p||_2^2 + lambda TV(x) for x on the working grid.
double tv_l2_objective(const ConvolutionOperator& op, const Plane& capture, const Plane& x,
                       double lambda);

}  // namespace pinmask
