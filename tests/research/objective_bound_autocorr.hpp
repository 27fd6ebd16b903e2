// A tighter upper bound on the analytic Wiener PSNR of any binary K-pinhole pattern than
// optimize/search/objective_bound.hpp's: the same relaxation in x(a) = |P^(a)|^2 / K^2, plus the
// constraints every binary pattern's cyclic autocorrelation satisfies (research: can the
// dim-light 0.5 dB gain of search over random patterns be ruled out?). Test-only code: built
// into tests/research's pinmask_research library, which no product target links.
//
// Derivation (notation of objective_bound.hpp; n x n pattern, lags d and frequencies a
// row-major in 0..n^2-1, a.d = a_r d_r + a_c d_c). The cyclic autocorrelation
//     r(d) = sum_i p(i) p(i + d) = (K^2 / n^2) sum_a x(a) cos(2 pi a.d / n)
// (x(a) = x(-a) for a real pattern, so the inverse DFT is the cosine sum) is LINEAR in x, and
// for every binary pattern with K ones: r(0) = K (Parseval), r(d) >= 0 for every d, and, when
// the pattern keeps the spacing rule (design/pattern/pattern.hpp: centres at least s cells apart on
// the torus, design/pattern/exclusion_grid.hpp's rows), r(d) = 0 at every lag d != 0 with a
// representative closer than s ("forbidden lags"). With x(0) = 1 fixed, multipliers mu (any sign)
// on r(0) = K and l(d) on r(d) >= 0 (l >= 0; any sign at a forbidden lag), scaled by K^2 / n^2, the
// Lagrangian stays separable per frequency:
//     D(mu, l) = g_0(1) - mu X - sum_{d != 0} l(d) + sum_{a != 0} min_{0<=x<=1} [g_a(x) + w_a x],
//     w_a = mu - sum_{d != 0} l(d) cos(2 pi a.d / n),   X = n^2 / K - 1,
// and D is a lower bound on N^2 MSE of every K-pattern (of the constrained set) for ANY such
// multipliers (weak duality: no convexity and no optimality of the multipliers needed). With
// l = 0 it is objective_bound's dual. Each inner minimum is bounded from below through the
// tangent of the convex g_a at the computed minimiser (as in objective_bound), so the value
// does not depend on how exactly the inner roots were solved.
//
// The multipliers are found by spectral projected gradient ascent (Barzilai-Borwein steps, a
// non-monotone Armijo search, projection onto the sign constraints) from objective_bound's mu
// and l = 0; D is concave and, where every group sees light, differentiable with
// dD/dmu = sum_{a != 0} x_a - X and dD/dl(d) = -(n^2 / K^2) r(d; x). The largest rigorous value
// seen is returned, so the bound is never looser than objective_bound's (same noise variance,
// objective_bound's bound_noise). Noise-free models (nu = 0) return objective_bound's value.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "optimize/search/objective_bound.hpp"

namespace pinmask {

// Lags d != 0 (row-major n x n) that the spacing rule with s = min_spacing_cells forbids: some
// representative (d_r + i n, d_c + j n) is closer than s (design/pattern/exclusion_grid.hpp's
// exclusion_rows, tolerance included). s = 0: none.
std::vector<char> forbidden_lags(int n, double min_spacing_cells);

// The lag part of w_a: -sum_{d != 0} lag[d] cos(2 pi a.d / n), a = 0..n^2-1 (lag: n^2 entries,
// lag[0] ignored). O(n^4).
std::vector<double> lag_weights(int n, const std::vector<double>& lag);

// InvalidInput unless `lag` has n^2 finite entries, non-negative at every lag d != 0 the spacing
// rule s does not forbid (the multipliers then give a valid bound). `field` names it.
void validate_lag_multipliers(const std::vector<double>& lag, int n, double min_spacing_cells,
                              const char* field);

// (n^2 / K^2) r(d) = sum_a x[a] cos(2 pi a.d / n), d = 0..n^2-1 (x: n^2 entries, x[0] the DC
// value). O(n^4).
std::vector<double> scaled_autocorrelation(int n, const std::vector<double>& x);

// The multipliers of the autocorrelation dual (already scaled by K^2 / n^2): `parseval` on
// r(0) = K (any sign), `lag[d]` on r(d) >= 0 (n^2 entries, lag[0] unused and 0).
struct AutocorrMultipliers {
    double parseval = 0.0;
    std::vector<double> lag;
};

// One evaluation of a dual D(mu, l): returns a RIGOROUS value and fills `x` with the inner
// minimisers x_a (n^2 entries, x[0] = 1), whose (n^2/K^2) r(d) give the supergradient.
using AutocorrDualOracle =
    std::function<double(const AutocorrMultipliers& m, std::vector<double>& x)>;

struct AutocorrAscent {
    AutocorrMultipliers best;  // the multipliers of the largest value seen
    double value = 0.0;        // that value (the oracle's, so rigorous)
    int iterations = 0;
    int evaluations = 0;
};

// Maximises a dual over (mu any sign, l(d) >= 0 where the rule does not forbid d; l = 0 when
// `lags` is false) by spectral projected gradient (Barzilai-Borwein steps, a non-monotone
// Armijo search) from `start` (projected first), supergradient dD/dmu = sum_{a != 0} x_a - X,
// dD/dl(d) = -(n^2/K^2) r(d; x). `step` is the first step's length in multiplier units per
// unit of the supergradient's largest entry. Stops after max_iterations, or when the best value
// has improved by less than stall_tolerance (relative) over stall_iterations steps.
AutocorrAscent ascend_autocorr_dual(const AutocorrDualOracle& oracle, AutocorrMultipliers start,
                                    int n, int holes, const std::vector<char>& forbidden, bool lags,
                                    double step, int max_iterations, int stall_iterations,
                                    double stall_tolerance);

struct AutocorrBoundOptions {
    int holes = 1;                   // K, 1..n^2
    double min_spacing_cells = 0.0;  // the spacing rule the patterns keep (0: none), finite >= 0
    bool lags = true;                // false: the Parseval multiplier only (objective_bound)
    // Dual ascent stops after max_iterations, or when the best rigorous value has improved by
    // less than stall_tolerance (relative) over stall_iterations steps. Valid either way.
    int max_iterations = 4000;
    int stall_iterations = 200;
    double stall_tolerance = 1e-7;

    // InvalidInput naming the field, value and rule (holes against n^2: `cells`).
    void validate(int cells) const;
};

struct AutocorrBound {
    int holes = 0;
    double mse = 0.0;           // lower bound on the expected per-pixel MSE (best dual value)
    double psnr_db = 0.0;       // 10 log10(1 / mse): the upper bound on the PSNR
    double parseval_mse = 0.0;  // objective_bound's value (the start point); mse >= it
    double noise_variance = 0.0;
    AutocorrMultipliers multipliers;  // the multipliers of `mse`
    std::vector<double> x;            // the inner minimisers at them, n x n, x[0] = 1
    // Largest violation of the lag constraints at x, relative to K: max over d != 0 of
    // max(0, -r(d)) (and |r(d)| at forbidden lags) and |r(0) - K|, divided by K.
    double violation = 0.0;
    int iterations = 0;
};

class AutocorrBoundModel {
  public:
    // As ObjectiveBoundModel (n divides the model's period; InvalidInput otherwise).
    AutocorrBoundModel(std::shared_ptr<const AnalyticWienerModel> model, int n);

    int n() const { return n_; }
    AutocorrBound bound(const AutocorrBoundOptions& options) const;

    // The rigorous dual value D (per-pixel MSE units) at the given multipliers for K = holes
    // and noise nu = N sigma^2. InvalidInput if `lag` has the wrong size or a negative entry at
    // a lag the spacing rule s does not forbid (such multipliers would not give a bound).
    // `x` (if not null) gets the inner minimisers.
    double dual_mse(const AutocorrMultipliers& m, int holes, double min_spacing_cells, double nu,
                    std::vector<double>* x = nullptr) const;
    // w_a = parseval - sum_{d != 0} lag(d) cos(2 pi a.d / n), a = 0..n^2-1.
    std::vector<double> weights(const AutocorrMultipliers& m) const;
    const ObjectiveBoundModel& parseval_model() const { return base_; }

  private:
    // The rigorous (tangent-bounded) dual value in N^2 MSE units; x gets the minimisers.
    double evaluate(const AutocorrMultipliers& m, int holes, double nu,
                    std::vector<double>& x) const;

    std::shared_ptr<const AnalyticWienerModel> model_;
    ObjectiveBoundModel base_;
    int n_ = 0;
};

}  // namespace pinmask
