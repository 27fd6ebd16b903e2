// The analytic Wiener error (optimize/metrics/analytic_error.hpp) in O(n^2) per pattern instead of
// O(m^2), m = n p, for the search objective after one move.
//
// h(k) = x(a) |K^(k)|^2 / |K^(0)|^2 with x(a) = |P^(a)|^2 / K^2, a = k mod n, so every one of
// the p^2 period frequencies aliased onto pattern frequency a sees the same x(a). Grouping:
//   mean(c^2) = (1/N^2) sum_a x(a) C(a),  C(a) = sum_{k = a mod n} kp(k) S(k)      (exact);
//   N^2 MSE   = sum_a F_a(...),  F_a the sum of the p^2 per-frequency terms of analytic_error:
//     optimal filter:  F_a(u) = sum_j S_j / (1 + e^u kp_j S_j),  u = log(x(a) / (N sigma^2))
//     fixed NSR:       F_a = G1_a(u) + N sigma^2 G2_a(u),  u = log x(a),
//                      G1_a = sum_j nsr^2 S_j / (h_j + nsr)^2,  G2_a = sum_j h_j / (h_j + nsr)^2.
// Each is a sum of smooth steps of width ~1 in u; it is tabulated once per pattern frequency on
// a uniform u grid (step 1/16) with its exact u-derivative and read by cubic Hermite
// interpolation (bound ~2e-8 of F_a; tests/optimize/metrics/test_aliased_wiener holds the total MSE
// to 1e-7 of the direct O(m^2) sum). The u range covers x in [1e-6, 1] and the noise variances the
// noise model can give for any K in 1..n^2; a frequency outside it (near spectral zero, noise-free
// model) is summed exactly over its p^2 aliases, so correctness never depends on the range, only
// speed does. Tables over 256 MB (n above ~250) are not built: every frequency is then summed
// exactly, O(m^2) per call as before.
//
// Tuned NSR (kTunedNsr: the scalar-NSR filter with its NSR chosen per pattern, as the simulated
// and decoded Wiener does): the fixed-NSR sums above at NSRs on a grid of kNsrGridPerDecade
// steps per decade over [10^kTuneMinLog10, 10^kTuneMaxLog10] (optimize/metrics/nsr_tuning), each
// grid NSR's tables built on first use; per pattern a descent on the grid from a start set by the
// noise level, then the parabola through the grid minimum and its two neighbours (in log NSR)
// gives the tuned MSE. The MSE is unimodal in log NSR for every pattern tried (as the golden
// section of evaluate_tuned_nsr assumes), so the result does not depend on the start. Each grid
// NSR's tables take n^2 x 223 x 32 bytes (1.8 MB at n = 16; kept up to 8 MB, n ~ 34; above
// that the exact sums are used, O(m^2) per grid NSR visited).
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "optimize/metrics/analytic_error.hpp"

namespace pinmask {

class AliasedWiener {
  public:
    // n must divide the model's period. Builds the tables: O(m^2 x grid points) once.
    AliasedWiener(std::shared_ptr<const AnalyticWienerModel> model, int n,
                  const WienerFilterSpec& filter);

    int n() const { return n_; }
    // Expected error of the pattern (n x n spectrum, P^(0) = K >= 1): same quantities as
    // AnalyticWienerModel::evaluate up to the tabulation error. O(n^2).
    AnalyticError evaluate(const ComplexPlane& pattern_spectrum) const;

    // Grid steps per decade of the tuned-NSR mode.
    static constexpr int kNsrGridPerDecade = 32;

  private:
    // F_a over its p^2 aliases; nsr: the fixed filter's NSR (ignored by the optimal filter).
    double exact_sum(int a, double x, double n_sigma2, double nsr) const;
    void build_tables(double u_lo, double u_hi);
    // Fixed-NSR tables [a][point][G1, dG1/du, G2, dG2/du] on u = log x for one NSR.
    std::vector<double> fixed_nsr_table(double nsr, double u_lo, int points) const;
    // N^2 MSE of the fixed NSR filter for the pattern's x(a), from one grid NSR's tables.
    double fixed_nsr_sum(int grid_index, const std::vector<double>& x, double nu) const;
    AnalyticError evaluate_tuned(const ComplexPlane& pattern_spectrum) const;

    // Tuned mode: one slot per grid NSR, built on first use (thread-safe).
    struct NsrSlot {
        std::once_flag once;
        std::vector<double> table;
    };
    std::vector<std::unique_ptr<NsrSlot>> nsr_slots_;
    double nsr_start_scale_ = 1.0;  // starting grid NSR = this * N sigma^2

    std::shared_ptr<const AnalyticWienerModel> model_;
    int n_ = 0, p_ = 0;
    WienerFilterSpec filter_;
    std::vector<double> capture_weight_;  // C(a), n^2
    std::vector<double> kp_, s_;          // aliases of a at [a p^2, (a + 1) p^2)
    int width_ = 0;                       // doubles per grid point: 2 (optimal) or 4 (fixed)
    int points_ = 0;                      // grid points per frequency, 0 = no table
    double u0_ = 0.0, step_ = 1.0 / 16.0;
    std::vector<double> table_;  // [a][point][value, d/du (, G2, dG2/du)]
};

}  // namespace pinmask
