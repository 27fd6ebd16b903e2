#include "tests/research/objective_bound_nsr.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>

#include "core/errors/error.hpp"
#include "optimize/simulate/image_quality.hpp"

namespace pinmask {
namespace {

// Initial NSR intervals: [0, 10^kFirstEdge], half-decade steps to 10^kLastEdge, [.., inf).
constexpr double kFirstEdgeLog10 = -10.0, kLastEdgeLog10 = 3.0, kEdgeStepLog10 = 0.5;
// Inner branch and bound: initial cells [0, kSmallestX] and factor-4 steps up to 1; at most
// kMaxCellSplits splits per group (the bound stays valid, only looser, if it is reached).
constexpr double kSmallestX = 1e-12, kInitialCellRatio = 4.0;
constexpr int kMaxCellSplits = 1000;
// Dual ascent: multiplier bracket by factors of 4 (at most kMaxExpansions), then bisection.
constexpr int kMaxExpansions = 200, kBisections = 24;
// Lag ascent per interval (NsrBoundOptions::lag_steps): first step as a fraction of |mu| per
// unit of the supergradient, and the relative gain below which it stops early.
constexpr double kLagFirstStepFraction = 1e-2, kLagStallTolerance = 1e-6;

// The fixed-NSR term (rho^2 S + nu h) / (h + rho)^2 with h = h_num in the numerator and h_den
// in the denominator (equal for a value; a cell's ends for its bound), written so that a huge or
// infinite rho (an interval reaching +inf) gives S, never inf / inf.
inline double scalar_term(double s, double rho, double nu, double h_num, double h_den) {
    const double q = 1.0 + h_den / rho;
    return (s + nu * h_num / (rho * rho)) / (q * q);
}

struct CellBound {
    double lo, hi, bound;
    bool operator>(const CellBound& o) const { return bound > o.bound; }
};

}  // namespace

void NsrBoundOptions::validate(int cells) const {
    if (holes < 1 || holes > cells) {
        throw invalid_field("holes", std::to_string(holes),
                            "must be in 1.." + std::to_string(cells) + " (the pattern's cells)");
    }
    if (!(nsr_ratio > 1.0) || !std::isfinite(nsr_ratio))
        throw invalid_field("nsr_ratio", std::to_string(nsr_ratio), "must be finite and > 1");
    if (max_intervals < 30 || max_intervals > 100000) {
        throw invalid_field("max_intervals", std::to_string(max_intervals),
                            "must be in 30..100000 (the initial intervals need 28)");
    }
    if (lag_steps < 0 || lag_steps > 100000)
        throw invalid_field("lag_steps", std::to_string(lag_steps), "must be in 0..100000");
    if (!(group_tolerance > 0.0) || !(group_tolerance < 1.0)) {
        throw invalid_field("group_tolerance", std::to_string(group_tolerance),
                            "must be in (0, 1)");
    }
    if (!(min_spacing_cells >= 0.0) || !std::isfinite(min_spacing_cells)) {
        throw invalid_field("min_spacing_cells", std::to_string(min_spacing_cells),
                            "must be finite and >= 0");
    }
    if (!multipliers.lag.empty()) {
        const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(cells))));
        validate_lag_multipliers(multipliers.lag, n, min_spacing_cells, "multipliers.lag");
        if (!std::isfinite(multipliers.parseval)) {
            throw invalid_field("multipliers.parseval", std::to_string(multipliers.parseval),
                                "must be finite");
        }
    }
}

NsrBoundModel::NsrBoundModel(std::shared_ptr<const AnalyticWienerModel> model, int n)
    : model_(model), optimal_(model, n), n_(n) {
    const int m = model_->period(), p = m / n, cells = n * n;
    const Plane& kp = model_->kernel_power();
    const Plane& s = model_->prior().power;
    blind_.assign(cells, 0.0);
    start_.assign(cells + 1, 0);
    for (int ar = 0; ar < n; ++ar)
        for (int ac = 0; ac < n; ++ac) {
            const int a = ar * n + ac;
            start_[a] = s_.size();
            for (int i = 0; i < p; ++i)
                for (int j = 0; j < p; ++j) {
                    const double sj = s(ar + i * n, ac + j * n), kj = kp(ar + i * n, ac + j * n);
                    if (kj > 0.0 && sj > 0.0) {
                        s_.push_back(sj);
                        kp_.push_back(kj);
                    } else if (!(kj > 0.0)) {
                        blind_[a] += sj;  // the filter passes nothing: error S at any NSR
                    }  // S = 0, kp > 0: the term is nu h / (h + r)^2 >= 0, dropped (a bound)
                }
        }
    start_[cells] = s_.size();
}

double NsrBoundModel::group_minimum(int a, const std::vector<double>& rho, double nu, double mu,
                                    double tolerance, double& argmin) const {
    const std::size_t j0 = start_[a], j1 = start_[a + 1];
    const auto value = [&](double x) {
        double v = blind_[a] + mu * x;
        for (std::size_t j = j0; j < j1; ++j) {
            const double h = kp_[j] * x;
            v += scalar_term(s_[j], rho[j], nu, h, h);
        }
        return v;
    };
    const auto cell = [&](double lo, double hi) {
        double v = blind_[a] + std::min(mu * lo, mu * hi);  // mu may be negative
        for (std::size_t j = j0; j < j1; ++j) {
            v += scalar_term(s_[j], rho[j], nu, kp_[j] * lo, kp_[j] * hi);
        }
        return CellBound{lo, hi, v};
    };
    double power = blind_[a];
    for (std::size_t j = j0; j < j1; ++j) power += s_[j];
    double best = value(0.0);
    argmin = 0.0;
    std::priority_queue<CellBound, std::vector<CellBound>, std::greater<CellBound>> queue;
    double lo = 0.0;
    for (double hi = kSmallestX; lo < 1.0; hi = std::min(1.0, hi * kInitialCellRatio)) {
        const double v = value(hi);
        if (v < best) best = v, argmin = hi;
        queue.push(cell(lo, hi));
        lo = hi;
    }
    const double tol = power * tolerance;
    for (int split = 0; split < kMaxCellSplits; ++split) {
        const CellBound c = queue.top();
        if (c.bound >= best - tol) break;
        queue.pop();
        const double mid = c.lo > 0.0 ? std::sqrt(c.lo * c.hi) : 0.5 * c.hi;
        const double v = value(mid);
        if (v < best) best = v, argmin = mid;
        queue.push(cell(c.lo, mid));
        queue.push(cell(mid, c.hi));
    }
    return std::min(best, queue.top().bound);
}

NsrBoundModel::Dual NsrBoundModel::make_dual(double r1, double r2, double nu, double target,
                                             double tolerance) const {
    Dual d{std::vector<double>(s_.size()), blind_[0], nu, target, tolerance};
    for (std::size_t j = 0; j < s_.size(); ++j) d.rho[j] = std::clamp(nu / s_[j], r1, r2);
    for (std::size_t j = start_[0]; j < start_[1]; ++j) {
        d.dc += scalar_term(s_[j], d.rho[j], nu, kp_[j], kp_[j]);
    }
    return d;
}

double NsrBoundModel::dual_value(const Dual& d, double mu, double& excess,
                                 std::vector<double>* xs) const {
    const int cells = n_ * n_;
    double v = d.dc - mu * d.target - d.lag_sum, sum = 0.0, x = 0.0;
    if (xs) xs->assign(static_cast<std::size_t>(cells), 1.0);
    for (int a = 1; a < cells; ++a) {
        const double w = d.offset ? mu + (*d.offset)[a] : mu;
        v += group_minimum(a, d.rho, d.nu, w, d.tolerance, x);
        if (xs) (*xs)[a] = x;
        sum += x;
    }
    excess = sum - d.target;
    return v;
}

// Dual ascent over mu of any sign (the scalar-NSR error can grow with x, so the multiplier of
// the equality sum x = X can be negative): bracket by factors of 4 from +-scale, then bisection.
// Every evaluated D(mu) is a valid bound; the largest is returned, its mu in `best_mu`.
double NsrBoundModel::maximise_dual(const Dual& d, double scale, double& best_mu) const {
    double best = -INFINITY, excess = 0.0;
    const auto eval = [&](double mu) {
        const double v = dual_value(d, mu, excess);
        if (v > best) best = v, best_mu = mu;
        return excess;
    };
    if (!(d.target > 0.0)) {  // K = n^2: x = 0 everywhere (mu large enough makes it the minimum)
        double v = d.dc;
        for (int a = 1; a < n_ * n_; ++a) {
            v += blind_[a];
            for (std::size_t j = start_[a]; j < start_[a + 1]; ++j) v += s_[j];
        }
        best_mu = 0.0;
        return v;
    }
    scale = std::max(std::fabs(scale), 1e-300);
    double lo = 0.0, hi = 0.0;
    const double e0 = eval(0.0);
    if (e0 > 0.0) {
        hi = scale;
        for (int i = 0; i < kMaxExpansions && eval(hi) > 0.0; ++i) lo = hi, hi *= 4.0;
    } else if (e0 < 0.0) {
        lo = -scale;
        for (int i = 0; i < kMaxExpansions && eval(lo) < 0.0; ++i) hi = lo, lo *= 4.0;
    }
    for (int i = 0; i < kBisections && lo < hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (eval(mid) > 0.0 ? lo : hi) = mid;
    }
    return best;
}

double NsrBoundModel::interval_bound(double r1, double r2, double nu, double target,
                                     double tolerance) const {
    double mu = 0.0;
    return maximise_dual(make_dual(r1, r2, nu, target, tolerance), 1.0, mu);
}

NsrBound NsrBoundModel::bound(const NsrBoundOptions& o) const {
    const int cells = n_ * n_;
    o.validate(cells);
    const double big_n = static_cast<double>(model_->period()) * model_->period();
    NsrBound b;
    b.holes = o.holes;
    const double nu = optimal_.bound_noise(o.holes);
    b.noise_variance = nu / big_n;
    ObjectiveBoundOptions oo;
    oo.holes = o.holes;
    const ObjectiveBound optimal = optimal_.bound(oo);
    const double target = static_cast<double>(cells) / o.holes - 1.0;
    // Lag multipliers (per interval: the given ones, then the ascent's), or none.
    const bool lags = !o.multipliers.lag.empty() || o.lag_steps > 0;
    AutocorrMultipliers start;
    start.parseval = o.multipliers.lag.empty() ? optimal.multiplier : o.multipliers.parseval;
    if (lags) {
        start.lag = o.multipliers.lag;
        start.lag.resize(static_cast<std::size_t>(cells), 0.0);
    }
    const std::vector<char> forbidden = forbidden_lags(n_, o.min_spacing_cells);
    // The interval's dual with m's lag part (`offset` holds its weights).
    const auto lagged_dual = [&](double r1, double r2, const AutocorrMultipliers& m,
                                 std::vector<double>& offset) {
        Dual d = make_dual(r1, r2, nu, target, o.group_tolerance);
        if (lags) {
            offset = lag_weights(n_, m.lag);
            d.offset = &offset;
            for (int i = 1; i < cells; ++i) d.lag_sum += m.lag[i];
        }
        return d;
    };
    // D at multipliers m over [r1, r2] (N^2 MSE units); xs (if not null) gets the minimisers.
    const auto dual_at = [&](double r1, double r2, const AutocorrMultipliers& m,
                             std::vector<double>* xs) {
        std::vector<double> offset;
        const Dual d = lagged_dual(r1, r2, m, offset);
        double excess = 0.0;
        return dual_value(d, m.parseval, excess, xs);
    };
    // Branch and bound on the NSR axis. An interval's bound starts as one dual value (at its
    // parent's best multipliers, or the start ones) and is maximised over mu (and, with
    // lag_steps, the lag multipliers) only when it is the lowest; a child's bound is at least
    // its parent's (its lower functions are larger at the same multipliers).
    struct Interval {
        double r1, r2, bound;
        AutocorrMultipliers m;
        bool maximised;
    };
    std::vector<Interval> iv;
    const auto cheap = [&](double r1, double r2, const AutocorrMultipliers& m, double floor) {
        const double v = dual_at(r1, r2, m, nullptr);
        return Interval{r1, r2, std::max(v, floor), m, false};
    };
    const auto lowest = [&] {
        return std::min_element(iv.begin(), iv.end(), [](const Interval& x, const Interval& y) {
            return x.bound < y.bound;
        });
    };
    if (nu > 0.0) {
        std::vector<double> edges{0.0};
        for (double e = kFirstEdgeLog10; e <= kLastEdgeLog10 + 1e-9; e += kEdgeStepLog10)
            edges.push_back(std::pow(10.0, e));
        edges.push_back(INFINITY);
        for (std::size_t i = 0; i + 1 < edges.size(); ++i)
            iv.push_back(cheap(edges[i], edges[i + 1], start, -INFINITY));
        while (static_cast<int>(iv.size()) < o.max_intervals) {
            const auto low = lowest();
            if (!low->maximised) {
                std::vector<double> offset;
                const Dual d = lagged_dual(low->r1, low->r2, low->m, offset);
                double mu = low->m.parseval;
                low->bound = std::max(low->bound, maximise_dual(d, low->m.parseval, mu));
                low->m.parseval = mu;
                if (o.lag_steps > 0) {
                    const double r1 = low->r1, r2 = low->r2;
                    const AutocorrDualOracle oracle = [&](const AutocorrMultipliers& m,
                                                          std::vector<double>& x) {
                        return dual_at(r1, r2, m, &x);
                    };
                    const AutocorrAscent up =
                        ascend_autocorr_dual(oracle, low->m, n_, o.holes, forbidden, true,
                                             kLagFirstStepFraction * std::fabs(mu), o.lag_steps,
                                             o.lag_steps, kLagStallTolerance);
                    if (up.value > low->bound) low->bound = up.value, low->m = up.best;
                }
                low->maximised = true;
                continue;
            }
            const Interval w = *low;
            if (w.r1 > 0.0 && std::isfinite(w.r2) && w.r2 / w.r1 < o.nsr_ratio) break;
            const double mid = w.r1 == 0.0            ? w.r2 / 10.0
                               : !std::isfinite(w.r2) ? w.r1 * 10.0
                                                      : std::sqrt(w.r1 * w.r2);
            *low = cheap(w.r1, mid, w.m, w.bound);
            iv.push_back(cheap(mid, w.r2, w.m, w.bound));
        }
    }
    double lowest_bound = 0.0;
    if (!iv.empty()) {
        const auto low = lowest();
        lowest_bound = low->bound;
        b.nsr_lo = low->r1;
        b.nsr_hi = low->r2;
    }
    b.intervals = static_cast<int>(iv.size());
    b.mse = std::max(lowest_bound / (big_n * big_n), optimal.mse);
    b.psnr_db = psnr_from_mse(b.mse);
    return b;
}

}  // namespace pinmask
