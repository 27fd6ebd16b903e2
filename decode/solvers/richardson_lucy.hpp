// Richardson-Lucy deconvolution (non-negative, multiplicative EM for Poisson data):
//   x <- x .* A^T(p ./ A x) ./ A^T 1
// Guards: the capture's negative values (noise after a dark-frame subtraction) are clipped to 0
// (RL models photon counts); where A x <= kRlTiny * max(p) the ratio is p / (kRlTiny max(p))
// (0 where p is 0 too); where A^T 1 <= kRlTiny * max(A^T 1) (working-grid pixels no capture
// pixel sees, linear model) x is set to 0. The PSF must be non-negative (InvalidInput).
// Starting point: the warm start clipped to >= 0, else the constant mean(p) / sum(a) (which
// reproduces the capture's mean for the cyclic model). A pixel that reaches 0 stays 0.
// Records: objective is the I-divergence sum(p log(p / A x) - p + A x) (0 log 0 = 0), which RL
// does not increase (it is the EM algorithm for this likelihood); residual ||A x - p||_2.
// Cost per iteration: two FFT pairs, and two fused pointwise passes (the ratio, the update).
// Precision: single_precision runs the iteration in float32 (FFTW float) on the operator H / H(0)
// and the iterate H(0) x (the update is invariant under that scaling; it keeps float32 values near
// 1 for a PSF of any scale); the start, the sums and the records are in double.
#pragma once

#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/solver_common.hpp"

namespace pinmask {

// Relative floor of the divisions of Richardson-Lucy.
inline constexpr double kRlTiny = 1e-12;

struct RichardsonLucyOptions : IterativeOptions {
    bool single_precision = false;  // iterate in float32 (FFTW float); see the header comment
};

// Runs RL; result.image is x (>= 0) on the operator's working grid. Throws InvalidInput for a PSF
// with negative values (pass the PSF the operator was built from) or bad options.
DecodeResult solve_richardson_lucy(const ConvolutionOperator& op, const Plane& psf,
                                   const Plane& capture, const RichardsonLucyOptions& options,
                                   const Plane* warm_start = nullptr);

// I-divergence sum(p log(p / q) - p + q) of non-negative p against q (q floored as in RL).
double i_divergence(const Plane& p, const Plane& q);

}  // namespace pinmask
