// TVQC: x = argmin TV(x) subject to ||A x - p||_2 <= eps [and x >= 0], the paper's decoder
// (l1-magic's "TV with quadratic constraints"), by a preconditioned Chambolle-Pock primal-dual
// method with the exact projection on the l2 ball.
//
// Saddle form: min_x max_y <K x, y> - F*(y) with K x = (grad x, beta A x[, gamma x]),
// F(g, q[, w]) = ||g||_{2,1} + indicator(||q - beta p||_2 <= beta eps) [+ indicator(w >= 0)],
// and G = 0. Non-negativity is a third dual block (so G stays 0), beta = sqrt(8) / rms|H| gives
// the data block the gradient's typical gain, gamma = 1.
// Iteration (Chambolle-Pock / PDHG with a Fourier-diagonal primal preconditioner, theta = 1):
//   x  <- x - tau M^-1 K^T y,   M = grad^T grad + beta^2 H^* H + gamma^2 I  (diagonal in Fourier)
//   y1 <- projection of y1 + sigma grad xbar on the pointwise unit l2 ball (prox of F1*)
//   yq <- v - sigma proj_B(v / sigma), v = yq + sigma beta A xbar   (prox of F2* by Moreau; B
//         the l2 ball of radius beta eps centred at beta p; the projection is exact)
//   yw <- min(0, yw + sigma gamma xbar)                               (prox of F3*)
//   xbar = 2 x_new - x_old.
// Step sizes: K^T K <= M (the crop has norm 1), so ||K M^-1/2|| <= 1 (a bound, no power
// iteration) and tau sigma = 0.99^2 < 1 converges (Pock and Chambolle 2011, preconditioned
// PDHG). tau / sigma is rebalanced by the adaptive PDHG rule of Goldstein, Li and Yuan (2015),
// alpha_0 = 0.5, eta = 0.95, Delta = 1.5, until alpha < 1e-3.
// Cost per iteration: two FFT pairs (two forward: the K^T y blocks; two inverse: M^-1 K^T y and
// beta H M^-1 K^T y) and fused pointwise loops without temporaries: one spectral pass (K^T y,
// its energy for the step balance, both preconditioned spectra, the 1/N folded in), one pass
// over the working grid (primal step, non-negativity block, gradient dual step with its
// residual and TV, and the next iteration's spatial K^T y, one row behind) and two over the
// capture window (beta A x, the ball's norm and the residual; then the projection). The
// iterates keep x and the step d = x_old - x_new, so xbar = x - d and grad x_old are never
// stored. Every buffer is allocated before the first iteration.
// Precision: single_precision runs the iteration in float32 (FFTW float; the data block held as
// beta A x and beta p, beta H having rms sqrt 8); the starting point, the exit repair, the sums,
// records and the returned residual and objective are in double. InvalidInput (field
// single_precision) when the iterates would leave float32's safe range
// (decode/solvers/precision.hpp). Starting point: the warm start, else the smooth feasible point
// x_f: the gradient-Tikhonov estimate IFFT[conj(H) P / (|H|^2 + lambda |D|^2)] with the largest
// lambda (bisection in log lambda, 16 steps over 24 decades) whose residual is <= 0.99 eps. Its
// cost is ~20 FFTs. Stopping: k >= 2, relative change of x <= tolerance and constraint violation
// (plus the norm of the negative part of x with nonnegative) <= tolerance * max(eps, ||p||).
//
// Limits and exit behaviour:
// - eps >= ||p||_2: x = 0 is feasible with TV = 0 and is returned at once (0 iterations).
// - eps = 0: the equality A x = p (exact where p is in the range of A); the start is x = 0.
// - At exit an infeasible iterate is repaired. eps > 0: the smallest step t towards x_f that
//   gives ||A x - p|| <= eps (a quadratic in t; TV rises by at most t (TV(x_f) - TV(x)) by
//   convexity). eps = 0: the pseudo-inverse correction x + t H^+ C^T (p - A x) (|H| below
//   1e-10 max|H| counts as 0), for the cyclic model the orthogonal projection on A x = p.
//   With nonnegative, x is clipped to >= 0 first and a repair that would make x negative is
//   skipped. converged is true when the stopping rule was met and the exit point satisfies the
//   constraint to kTvqcFeasibilityTol (relative to max(eps, ||p||)).
// - eps from the noise: eps = sigma sqrt(N) sqrt(1 + 2 sqrt(2 / N)) (N = capture pixels), the
//   l1-magic choice: ||n||^2 / sigma^2 is chi-square with mean N and standard deviation
//   sqrt(2 N), so eps^2 is the mean plus two standard deviations (about 98% of draws inside).
// Records: objective TV(x), residual ||A x - p||_2 / eps (<= 1 is feasible), or / ||p||_2 when
// eps = 0.
#pragma once

#include <optional>

#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/solver_common.hpp"

namespace pinmask {

// Relative constraint violation (||A x - p|| - eps) / max(eps, ||p||) accepted as feasible.
inline constexpr double kTvqcFeasibilityTol = 1e-6;

struct TvqcOptions : IterativeOptions {
    double eps = 0.0;  // >= 0, same units as the capture
    bool nonnegative = false;
    bool single_precision = false;  // iterate in float32 (FFTW float); see the header comment
};

// eps = sigma sqrt(N) sqrt(1 + 2 sqrt(2 / N)) for N >= 1 measurements and noise sigma >= 0.
double tvqc_eps_from_sigma(double noise_sigma, long long n_measurements);

// Runs the primal-dual method; result.image is x on the operator's working grid.
DecodeResult solve_tvqc(const ConvolutionOperator& op, const Plane& capture,
                        const TvqcOptions& options, const Plane* warm_start = nullptr);

}  // namespace pinmask
