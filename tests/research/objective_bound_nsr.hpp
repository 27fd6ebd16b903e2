// The upper bound of optimize/search/objective_bound.hpp for the scalar-NSR Wiener filter with ANY
// NSR (so in particular the tuned NSR that decode, the simulation and `search --photons` use):
// a provable upper bound on the expected PSNR that filter reaches with any K-pinhole pattern.
// It is tighter than the optimal filter's bound wherever one scalar NSR cannot match the prior
// (at dim light by 1-2 dB), at the cost of a global search (seconds per K, not milliseconds).
// Test-only code (tests/research's pinmask_research library, which no product target links).
//
// Derivation (notation of objective_bound.hpp; h = x kp, B = nu = N sigma^2). The fixed-NSR
// filter's per-frequency error is f(x; r) = (r^2 S + B h) / (h + r)^2 (analytic_error.hpp).
// As a function of r it falls for r < B/S and rises after (df/dr = 2 h (r S - B) / (h + r)^3),
// so over an NSR interval [r1, r2] its smallest value, for every x at once, is at
// rho = clamp(B / S, r1, r2): f(x; r) >= f(x; rho) for all r in [r1, r2]. Hence for each
// interval, N^2 MSE >= sum_a G_a(x_a) with G_a(x) = sum_{aliases} f(x; rho_j), and the same
// Lagrange dual as objective_bound (weak duality needs no convexity) bounds the minimum over
// the relaxed set: D(mu) = sum_{a != 0} min_{0<=x<=1} [G_a(x) + mu x] - mu X + G_0(1). G_a is
// not convex, so each inner minimum is found by branch and bound on x with a rigorous cell
// bound: on [xl, xh] each term is >= (rho^2 S + B kp xl) / (kp xh + rho)^2. The NSR axis
// [0, inf) is covered by intervals (branch and bound again: the interval with the smallest
// bound is split until it is narrow); the result is the smallest interval bound, never
// above the optimal filter's bound's PSNR (their maximum MSE is kept). Noise as in
// objective_bound (Gaussian SNR: the smallest variance of the relaxed set; f increases with B).
// With autocorrelation multipliers (objective_bound_autocorr.hpp) each interval's dual gains
// their terms: w_a = mu + lag_weights(l)[a] in place of mu and the constant -sum l; valid for the
// patterns that keep the spacing rule the multipliers' signs assume. A cell's bound on the
// linear term is min(w xl, w xh), since w may be negative.
#pragma once

#include <memory>

#include "optimize/search/objective_bound.hpp"
#include "tests/research/objective_bound_autocorr.hpp"

namespace pinmask {

struct NsrBoundOptions {
    int holes = 1;  // K, 1..n^2
    // An NSR interval whose bound is the smallest is split until r2 / r1 is below this.
    double nsr_ratio = 1.05;
    int max_intervals = 400;  // cap on NSR intervals (the bound stays valid, only looser)
    // Inner branch and bound stops when every cell's bound is within this fraction of the
    // group's total prior power of the best value found (so it adds at most this to the MSE
    // relative to the prior's non-DC power).
    double group_tolerance = 1e-3;
    // Autocorrelation multipliers (tests/research/objective_bound_autocorr.hpp; typically the
    // optimal filter's, AutocorrBound::multipliers) added to every interval's dual: the lag part
    // is kept fixed, the Parseval multiplier is maximised per interval as without them (their
    // `parseval` is its start). Empty `lag`: Parseval only. Valid for the patterns that keep
    // the spacing rule min_spacing_cells (which allows negative lag multipliers at the lags it
    // forbids).
    AutocorrMultipliers multipliers;
    double min_spacing_cells = 0.0;
    // > 0: when an NSR interval is maximised, its lag multipliers (and mu) are also raised by
    // at most this many steps of ascend_autocorr_dual (from `multipliers`, or from zero lags);
    // each step costs one or more dual evaluations (a branch and bound per group).
    int lag_steps = 0;

    void validate(int cells) const;  // InvalidInput naming field, value and rule
};

struct NsrBound {
    int holes = 0;
    double mse = 0.0;      // lower bound on the fixed-NSR filter's expected MSE, any NSR
    double psnr_db = 0.0;  // the upper bound on its PSNR
    double nsr_lo = 0.0, nsr_hi = 0.0;  // the NSR interval that gave the bound
    int intervals = 0;                  // NSR intervals at the end
    double noise_variance = 0.0;
};

class NsrBoundModel {
  public:
    NsrBoundModel(std::shared_ptr<const AnalyticWienerModel> model, int n);

    NsrBound bound(const NsrBoundOptions& options) const;
    // Lower bound on N^2 MSE over the relaxed set for every NSR in [r1, r2] (r2 may be +inf),
    // at noise nu = N sigma^2 and sum target X (exposed for tests).
    double interval_bound(double r1, double r2, double nu, double target,
                          double group_tolerance = 1e-3) const;

  private:
    // One NSR interval's lower functions: per-term NSR rho, the DC group's error, noise, X.
    // offset: the lag multipliers' per-group weight (lag_weights; empty: none), lag_sum their
    // sum (the dual's constant -sum l).
    struct Dual {
        std::vector<double> rho;
        double dc, nu, target, tolerance;
        const std::vector<double>* offset = nullptr;
        double lag_sum = 0.0;
    };
    Dual make_dual(double r1, double r2, double nu, double target, double tolerance) const;
    // D(mu) (N^2 MSE units); `excess` gets sum x_a(mu) - X at the inner minimisers.
    // xs (if not null) gets the inner minimisers (n^2 entries, xs[0] = 1).
    double dual_value(const Dual& d, double mu, double& excess,
                      std::vector<double>* xs = nullptr) const;
    double maximise_dual(const Dual& d, double scale, double& best_mu) const;
    // Rigorous lower bound on min_{0<=x<=1} G_a(x) + mu x; `argmin` gets the best point seen.
    double group_minimum(int a, const std::vector<double>& rho, double nu, double mu,
                         double tolerance, double& argmin) const;

    std::shared_ptr<const AnalyticWienerModel> model_;
    ObjectiveBoundModel optimal_;
    int n_ = 0;
    std::vector<double> s_, kp_, blind_;  // per alias with kp > 0 and S > 0; blind: kp = 0
    std::vector<std::size_t> start_;
};

}  // namespace pinmask
