// A provable upper bound on the analytic Wiener PSNR (optimize/metrics/analytic_error.hpp) that ANY
// binary n x n pattern with K pinholes can reach, for a fixed camera kernel, scene prior and
// noise model: it tells whether a PSNR target (e.g. in dim light) is reachable at all.
//
// Derivation, in the conventions of optimize/metrics/analytic_error.hpp and
// optimize/metrics/aliased_wiener.hpp. With x(a) = |P^(a)|^2 / K^2 for the n^2 pattern frequencies
// a, h(k) = x(k mod n) kp(k), kp = |K^|^2 / |K^(0)|^2, and nu = N sigma^2 (N = m^2 pixels of the
// period), the per-frequency optimal Wiener filter's MSE is
//     N^2 MSE = sum_a g_a(x(a)),   g_a(x) = sum_{k = a mod n} S(k) nu / (x kp(k) S(k) + nu),
// a sum of convex decreasing functions of x (each term is S / (1 + c x), c >= 0). The optimal
// filter minimises the expected squared error at every frequency, so g_a lower-bounds the error
// of every linear (per-frequency) decoder of this model, in particular the fixed and tuned-NSR
// Wiener that decode, the simulation and `search --photons` use.
// Every binary pattern with K ones satisfies: x(0) = 1 (P^(0) = K); 0 <= x(a) <= 1
// (|P^(a)| <= K); sum_a x(a) = n^2 / K (Parseval: sum_a |P^(a)|^2 = n^2 sum p^2 = n^2 K);
// x(a) = x(-a). Dropping the symmetry and relaxing the sum to "<= n^2/K" (g_a decreasing, so
// this cannot raise the minimum over the binary patterns' set, only lower the relaxed one)
// leaves a separable convex problem:
//     minimise sum_{a != 0} g_a(x_a)  s.t.  0 <= x_a <= 1,  sum_{a != 0} x_a <= X = n^2/K - 1.
// Its Lagrange dual, for any multiplier mu >= 0,
//     D(mu) = sum_{a != 0} min_{0 <= x <= 1} [g_a(x) + mu x] - mu X  (+ g_0(1)),
// is a lower bound on N^2 MSE of every K-pattern (weak duality: no optimality of mu needed).
// The water-filling solution: each x_a(mu) solves -g_a'(x) = mu clipped to [0, 1]; mu by
// bisection on log mu so that sum x_a(mu) = X. Each inner minimum is bounded from below through
// its tangent at the computed x_a (convexity), so the reported bound does not depend on how
// exactly the inner roots or mu were found; the primal value at x(mu) is reported beside it
// (their difference is the duality gap, ~1e-10 relative).
//
// Noise: the photon model's variance depends on K (total light) and the prior's mean scene
// value, not on the pattern: the bound uses it exactly. The Gaussian-SNR model's variance is
// mean(c^2) / SNR with mean(c^2) = (1/N^2) sum_a x(a) C(a), C(a) = sum_{k = a mod n} kp S,
// which the pattern changes; the bound uses the smallest variance any relaxed point has
// (fill X onto the frequencies of smallest C(a) first), which is valid because g_a increases
// with nu, but looser. In general the variance is taken at the smallest mean(c^2) of the
// relaxed set, which is the smallest variance for every noise model here (each is
// non-decreasing in mean(c^2)). A noise-free model (nu = 0) gives the frequencies the kernel
// cannot pass (kp S = 0) as the whole bound.
#pragma once

#include <memory>
#include <vector>

#include "optimize/metrics/analytic_error.hpp"

namespace pinmask {

struct ObjectiveBoundOptions {
    int holes = 1;  // K, 1..n^2
    // Bisection on log mu stops when sum x_a(mu) is within this of X (relative to n^2), or
    // after max_iterations; the bound is valid either way (dual value), only the gap grows.
    double sum_tolerance = 1e-13;
    int max_iterations = 200;

    // InvalidInput naming the field, value and rule (holes against n^2: `cells`).
    void validate(int cells) const;
};

struct ObjectiveBound {
    int holes = 0;
    double mse = 0.0;          // lower bound on the expected per-pixel MSE (dual value)
    double psnr_db = 0.0;      // 10 log10(1 / mse): the upper bound on the PSNR
    double relaxed_mse = 0.0;  // the relaxed problem's value at x (primal; >= mse)
    double noise_variance = 0.0;
    double multiplier = 0.0;  // mu (0: the sum constraint is not active)
    std::vector<double> x;    // relaxed x(a) = |P^(a)|^2 / K^2, n x n row-major, x[0] = 1
    int iterations = 0;
};

class ObjectiveBoundModel {
  public:
    // Groups the model's kernel power and prior by the n x n pattern frequencies (n divides
    // the model's period; InvalidInput otherwise).
    ObjectiveBoundModel(std::shared_ptr<const AnalyticWienerModel> model, int n);

    int n() const { return n_; }
    ObjectiveBound bound(const ObjectiveBoundOptions& options) const;

    // The per-frequency function g_a(x) (N^2 MSE units) and its slope g_a'(x) at noise nu =
    // N sigma^2; a in 0..n^2-1 row-major.
    double group_error(int a, double x, double nu) const;
    double group_slope(int a, double x, double nu) const;
    // nu = N sigma^2 used for K pinholes (see the noise paragraph above).
    double bound_noise(int holes) const;
    // Solves -g_a'(x) = mu on [0, 1] (clipped): the minimiser of g_a(x) + mu x, any sign of mu.
    double solve_group(int a, double mu, double nu) const;

  private:
    std::shared_ptr<const AnalyticWienerModel> model_;
    int n_ = 0, p_ = 0;
    // Per group a: the terms with kp S > 0 as (S, c = kp S) at [start_[a], start_[a + 1]);
    // blind_[a]: sum of S over the terms with kp S = 0 (error that no pattern can remove).
    std::vector<double> s_, c_, blind_;
    std::vector<std::size_t> start_;
    std::vector<double> capture_weight_;  // C(a)
};

}  // namespace pinmask
