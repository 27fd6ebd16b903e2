// TVQC: x = argmin TV(x) subject to ||A x - p||_2 <= eps [and x >= 0], the paper's decoder
// (l1-magic's "TV with quadratic constraints"), by the Chambolle-Pock primal-dual method.
//
// Saddle form: K x = (grad x, beta A x), F(g, q) = ||g||_{2,1} + indicator(||q - beta p|| <=
// beta eps), G(x) = indicator(x >= 0) or 0. beta = sqrt(8) / max|H| balances the two blocks,
// so ||K||^2 <= ||grad||^2 + beta^2 ||A||^2 <= 8 + 8 = 16 = L^2 (bounds, not power iteration).
// Iteration (theta = 1):
//   y1 <- projection of y1 + sigma grad xbar on the pointwise unit l2 ball (prox of F1*)
//   y2 <- v - sigma proj_B(v / sigma), v = y2 + sigma beta A xbar   (prox of F2*, Moreau: B is
//         the l2 ball of radius beta eps centred at beta p; exact projection)
//   x  <- prox_G(x - tau (grad^T y1 + beta A^T y2)),  xbar = 2 x_new - x_old
// Steps start at tau = sigma = 0.99 / L and are rebalanced (tau sigma kept constant) by the
// adaptive PDHG rule of Goldstein, Li and Yuan (2015): alpha_0 = 0.5, eta = 0.95, Delta = 1.5.
// Cost per iteration: two FFT pairs (A x and A^T y2).
//
// Limits and exit behaviour:
// - eps >= ||p||_2: x = 0 is feasible with TV = 0 and is returned at once (0 iterations).
// - eps = 0: the equality A x = p (exact where p is in the range of A).
// - At exit the iterate is made feasible when it is not: x <- x + t delta with the pseudo-inverse
//   correction delta = H^+ C^T (p - A x) (|H| below 1e-10 max|H| treated as 0) and the smallest
//   t in [0, 1] that gives ||A x - p|| <= eps (a quadratic in t). For the cyclic model without
//   spectral zeros t = 1 reaches A x = p, so a feasible point is always reached; otherwise the
//   best t is taken and the remaining violation shows in the residual. With nonnegative the
//   correction is skipped when it would make x negative. converged is true when the iteration
//   met the tolerance and the exit point satisfies the constraint to kTvqcFeasibilityTol.
// - eps from the noise: eps = sigma sqrt(N) sqrt(1 + 2 sqrt(2 / N)) (N = capture pixels), the
//   l1-magic choice: ||n||^2 / sigma^2 is chi-square with mean N and standard deviation
//   sqrt(2 N), so eps^2 is the mean plus two standard deviations (about 98% of draws inside).
// Records: objective TV(x), residual ||A x - p||_2 / eps (<= 1 is feasible), or / ||p||_2 when
// eps = 0.
#pragma once

#include <optional>

#include "decode/convolution.hpp"
#include "decode/decoder.hpp"
#include "decode/solver_common.hpp"

namespace pinmask {

// Relative constraint violation (||A x - p|| - eps) / max(eps, ||p||) accepted as feasible.
inline constexpr double kTvqcFeasibilityTol = 1e-6;

struct TvqcOptions : IterativeOptions {
    double eps = 0.0;  // >= 0, same units as the capture
    bool nonnegative = false;
};

// eps = sigma sqrt(N) sqrt(1 + 2 sqrt(2 / N)) for N >= 1 measurements and noise sigma >= 0.
double tvqc_eps_from_sigma(double noise_sigma, long long n_measurements);

// Runs Chambolle-Pock; result.image is x on the operator's working grid.
DecodeResult solve_tvqc(const ConvolutionOperator& op, const Plane& capture,
                        const TvqcOptions& options, const Plane* warm_start = nullptr);

}  // namespace pinmask
