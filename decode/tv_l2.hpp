// TV-L2 deconvolution: x = argmin 1/2 ||A x - p||_2^2 + lambda TV(x) [+ indicator(x >= 0)],
// isotropic TV with periodic differences (decode/gradient.hpp), A a convolution model
// (decode/convolution.hpp), by ADMM.
//
// Splits (scaled duals u, v, eta; penalties rho for z and w, rho_s for s):
//   z = grad x,  w = x (only with nonnegative),  s = H x (only for the linear model).
// x-step, diagonal in Fourier space:
//   cyclic: (|H|^2 + rho |D|^2 + rho_w) X = conj(H) P + rho F[grad^T (z - u)] + rho_w F[w - v]
//   linear: (rho_s |H|^2 + rho |D|^2 + rho_w) X = rho_s conj(H) F[s - eta] + (same terms)
//   with |D|^2 = 4 sin^2(pi k / R) + 4 sin^2(pi l / C) and rho_w = rho when nonnegative, else 0.
// z-step: isotropic shrinkage of grad x + u by lambda / rho; w-step: max(0, x + v);
// s-step (pointwise): s = (C^T p + rho_s (H x + eta)) / (C^T C 1 + rho_s).
// Penalties: rho starts at the mean of |H|^2 over the spectrum (rho_s at 1) unless given, and
// both follow residual balancing (x2 / /2 when one residual exceeds 10x the other) every 10
// iterations during the first half of the run, then stay fixed (ADMM convergence holds).
// The estimate returned is x, or w (exactly >= 0) when nonnegative. Objective in the records:
// 1/2 ||A x - p||_2^2 + lambda TV(x) of that estimate; residual ||A x - p||_2.
// Cost per iteration: one FFT pair (cyclic), two (linear), plus one when recording with
// nonnegative. Starting point: the warm start, else x = 0.
#pragma once

#include "decode/convolution.hpp"
#include "decode/decoder.hpp"
#include "decode/solver_common.hpp"

namespace pinmask {

struct TvL2Options : IterativeOptions {
    double lambda = 1e-3;  // >= 0
    bool nonnegative = false;
    double rho = 0.0;  // initial ADMM penalty (> 0), or 0 for the automatic choice
};

// Runs ADMM; result.image is x on the operator's working grid (crop it with crop_to_capture).
// Throws InvalidInput for a capture of the wrong size or options out of range.
DecodeResult solve_tv_l2(const ConvolutionOperator& op, const Plane& capture,
                         const TvL2Options& options, const Plane* warm_start = nullptr);

// 1/2 ||A x - p||_2^2 + lambda TV(x) for x on the working grid.
double tv_l2_objective(const ConvolutionOperator& op, const Plane& capture, const Plane& x,
                       double lambda);

}  // namespace pinmask
