#include "tests/research/objective_bound_autocorr.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>

#include "core/errors/error.hpp"
#include "design/pattern/exclusion_grid.hpp"
#include "optimize/simulate/image_quality.hpp"

namespace pinmask {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
// Non-monotone Armijo search: sufficient-decrease factor, memory, step halvings per search.
constexpr double kArmijo = 1e-4;
constexpr std::size_t kMemory = 10;
constexpr int kMaxHalvings = 40;
// Barzilai-Borwein step clamp (relative to the first step) and the first step as a fraction of
// |mu| per unit of the gradient's largest entry.
constexpr double kStepClamp = 1e12, kFirstStepFraction = 1e-2;

}  // namespace

std::vector<char> forbidden_lags(int n, double min_spacing_cells) {
    if (n < 1) throw invalid_field("n", std::to_string(n), "must be >= 1");
    if (!(min_spacing_cells >= 0.0) || !std::isfinite(min_spacing_cells)) {
        throw invalid_field("min_spacing_cells", std::to_string(min_spacing_cells),
                            "must be finite and >= 0");
    }
    std::vector<char> out(static_cast<std::size_t>(n) * n, 0);
    for (const ExclusionRow& row : exclusion_rows(min_spacing_cells)) {
        const int r = ((row.dr % n) + n) % n;
        for (int dc = -row.half_width; dc <= row.half_width; ++dc) {
            const int c = ((dc % n) + n) % n;
            if (r != 0 || c != 0) out[static_cast<std::size_t>(r) * n + c] = 1;
        }
    }
    return out;
}

std::vector<double> lag_weights(int n, const std::vector<double>& lag) {
    const int cells = n * n;
    std::vector<double> cs(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) cs[k] = std::cos(kTwoPi * k / n);
    std::vector<double> w(cells, 0.0);
    for (int d = 1; d < cells; ++d) {
        const double l = lag[d];
        if (l == 0.0) continue;
        const int dr = d / n, dc = d % n;
        for (int ar = 0; ar < n; ++ar)
            for (int ac = 0; ac < n; ++ac) w[ar * n + ac] -= l * cs[(ar * dr + ac * dc) % n];
    }
    return w;
}

std::vector<double> scaled_autocorrelation(int n, const std::vector<double>& x) {
    const int cells = n * n;
    std::vector<double> cs(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) cs[k] = std::cos(kTwoPi * k / n);
    std::vector<double> r(cells, 0.0);
    for (int d = 0; d < cells; ++d) {
        const int dr = d / n, dc = d % n;
        double sum = 0.0;
        for (int ar = 0; ar < n; ++ar)
            for (int ac = 0; ac < n; ++ac) sum += x[ar * n + ac] * cs[(ar * dr + ac * dc) % n];
        r[d] = sum;
    }
    return r;
}

AutocorrAscent ascend_autocorr_dual(const AutocorrDualOracle& oracle, AutocorrMultipliers start,
                                    int n, int holes, const std::vector<char>& forbidden, bool lags,
                                    double step, int max_iterations, int stall_iterations,
                                    double stall_tolerance) {
    const int cells = n * n;
    const double target = static_cast<double>(cells) / holes - 1.0;
    const auto project = [&](AutocorrMultipliers& m) {
        for (int d = 1; d < cells; ++d) {
            if (!lags)
                m.lag[d] = 0.0;
            else if (!forbidden[d])
                m.lag[d] = std::max(0.0, m.lag[d]);
        }
    };
    // The supergradient of D at the minimisers x.
    const auto supergradient = [&](const std::vector<double>& x) {
        std::vector<double> g = scaled_autocorrelation(n, x);
        double sum = 0.0;
        for (int a = 1; a < cells; ++a) sum += x[a];
        for (int d = 1; d < cells; ++d) g[d] = -g[d];
        g[0] = sum - target;
        return g;
    };
    AutocorrAscent out;
    project(start);
    AutocorrMultipliers z = start;
    std::vector<double> x;
    double value = oracle(z, x);
    ++out.evaluations;
    std::vector<double> grad = supergradient(x);
    out.best = z;
    out.value = value;
    double gmax = 0.0;
    for (double g : grad) gmax = std::max(gmax, std::fabs(g));
    const double first = std::max(step, 1e-300) / std::max(gmax, 1e-300);
    double alpha = first;
    std::deque<double> recent{value};
    double stall_ref = out.value;
    int since = 0;
    for (out.iterations = 0; out.iterations < max_iterations; ++out.iterations) {
        AutocorrMultipliers trial = z;  // projected step along the supergradient
        trial.parseval += alpha * grad[0];
        for (int d = 1; d < cells; ++d) trial.lag[d] += alpha * grad[d];
        project(trial);
        std::vector<double> dir(cells);
        dir[0] = trial.parseval - z.parseval;
        double slope = grad[0] * dir[0], dnorm = std::fabs(dir[0]);
        for (int d = 1; d < cells; ++d) {
            dir[d] = trial.lag[d] - z.lag[d];
            slope += grad[d] * dir[d];
            dnorm = std::max(dnorm, std::fabs(dir[d]));
        }
        if (!(dnorm > 0.0) || !(slope > 0.0)) break;
        const double floor = *std::min_element(recent.begin(), recent.end());
        double t = 1.0, v = value;
        AutocorrMultipliers next = z;
        std::vector<double> x_next;
        bool accepted = false;
        for (int h = 0; h < kMaxHalvings; ++h, t *= 0.5) {
            next.parseval = z.parseval + t * dir[0];
            for (int d = 1; d < cells; ++d) next.lag[d] = z.lag[d] + t * dir[d];
            v = oracle(next, x_next);
            ++out.evaluations;
            if (v > out.value) out.value = v, out.best = next;
            if (v >= floor + kArmijo * t * slope) {
                accepted = true;
                break;
            }
        }
        if (!accepted) break;
        const std::vector<double> grad_next = supergradient(x_next);
        // Barzilai-Borwein step for the minimisation of -D: s = next - z, y = -(g' - g).
        double ss = 0.0, sy = 0.0;
        for (int d = 0; d < cells; ++d) {
            const double sd = d == 0 ? next.parseval - z.parseval : next.lag[d] - z.lag[d];
            ss += sd * sd;
            sy -= sd * (grad_next[d] - grad[d]);
        }
        alpha = sy > 0.0 ? std::clamp(ss / sy, first / kStepClamp, first * kStepClamp)
                         : first * kStepClamp;
        z = next;
        value = v;
        grad = grad_next;
        recent.push_back(value);
        if (recent.size() > kMemory) recent.pop_front();
        if (out.value - stall_ref > stall_tolerance * std::fabs(stall_ref)) {
            stall_ref = out.value;
            since = 0;
        } else if (++since >= stall_iterations) {
            break;
        }
    }
    return out;
}

void validate_lag_multipliers(const std::vector<double>& lag, int n, double min_spacing_cells,
                              const char* field) {
    const int cells = n * n;
    if (lag.size() != static_cast<std::size_t>(cells)) {
        throw invalid_field(field, std::to_string(lag.size()) + " entries",
                            "must have n^2 = " + std::to_string(cells));
    }
    const std::vector<char> forbidden = forbidden_lags(n, min_spacing_cells);
    for (int d = 1; d < cells; ++d) {
        if (!std::isfinite(lag[d]) || (!forbidden[d] && lag[d] < 0.0)) {
            throw invalid_field(std::string(field) + "[" + std::to_string(d) + "]",
                                std::to_string(lag[d]),
                                "must be finite, and >= 0 at a lag the spacing rule allows");
        }
    }
}

void AutocorrBoundOptions::validate(int cells) const {
    if (holes < 1 || holes > cells) {
        throw invalid_field("holes", std::to_string(holes),
                            "must be in 1.." + std::to_string(cells) + " (the pattern's cells)");
    }
    if (!(min_spacing_cells >= 0.0) || !std::isfinite(min_spacing_cells)) {
        throw invalid_field("min_spacing_cells", std::to_string(min_spacing_cells),
                            "must be finite and >= 0");
    }
    if (max_iterations < 0 || max_iterations > 1000000) {
        throw invalid_field("max_iterations", std::to_string(max_iterations),
                            "must be in 0..1000000");
    }
    if (stall_iterations < 1 || stall_iterations > 1000000) {
        throw invalid_field("stall_iterations", std::to_string(stall_iterations),
                            "must be in 1..1000000");
    }
    if (!(stall_tolerance >= 0.0) || !(stall_tolerance < 1.0)) {
        throw invalid_field("stall_tolerance", std::to_string(stall_tolerance),
                            "must be in [0, 1)");
    }
}

AutocorrBoundModel::AutocorrBoundModel(std::shared_ptr<const AnalyticWienerModel> model, int n)
    : model_(model), base_(model, n), n_(n) {}

std::vector<double> AutocorrBoundModel::weights(const AutocorrMultipliers& m) const {
    std::vector<double> w = lag_weights(n_, m.lag);
    for (double& v : w) v += m.parseval;
    return w;
}

double AutocorrBoundModel::evaluate(const AutocorrMultipliers& m, int holes, double nu,
                                    std::vector<double>& x) const {
    const int cells = n_ * n_;
    const double target = static_cast<double>(cells) / holes - 1.0;
    const std::vector<double> w = weights(m);
    double lag_sum = 0.0;
    for (int d = 1; d < cells; ++d) lag_sum += m.lag[d];
    double v = base_.group_error(0, 1.0, nu) - m.parseval * target - lag_sum;
    x.assign(cells, 0.0);
    x[0] = 1.0;
    for (int a = 1; a < cells; ++a) {
        // Inner minimum bounded below by the tangent at the computed minimiser (g_a convex).
        const double xa = base_.solve_group(a, w[a], nu);
        x[a] = xa;
        const double slope = base_.group_slope(a, xa, nu) + w[a];
        v += base_.group_error(a, xa, nu) + w[a] * xa + std::min(-slope * xa, slope * (1.0 - xa));
    }
    return v;
}

double AutocorrBoundModel::dual_mse(const AutocorrMultipliers& m, int holes,
                                    double min_spacing_cells, double nu,
                                    std::vector<double>* x) const {
    const int cells = n_ * n_;
    if (holes < 1 || holes > cells) {
        throw invalid_field("holes", std::to_string(holes),
                            "must be in 1.." + std::to_string(cells) + " (the pattern's cells)");
    }
    validate_lag_multipliers(m.lag, n_, min_spacing_cells, "lag");
    if (!std::isfinite(m.parseval))
        throw invalid_field("parseval", std::to_string(m.parseval), "must be finite");
    if (!(nu > 0.0)) throw invalid_field("nu", std::to_string(nu), "must be > 0");
    std::vector<double> xs;
    const double v = evaluate(m, holes, nu, xs);
    if (x) *x = xs;
    const double big_n = static_cast<double>(model_->period()) * model_->period();
    return v / (big_n * big_n);
}

AutocorrBound AutocorrBoundModel::bound(const AutocorrBoundOptions& o) const {
    const int cells = n_ * n_;
    o.validate(cells);
    const double big_n = static_cast<double>(model_->period()) * model_->period();
    const double big_n2 = big_n * big_n;
    ObjectiveBoundOptions bo;
    bo.holes = o.holes;
    const ObjectiveBound base = base_.bound(bo);
    AutocorrBound b;
    b.holes = o.holes;
    b.parseval_mse = base.mse;
    b.noise_variance = base.noise_variance;
    b.mse = base.mse;
    b.x = base.x;
    b.multipliers.parseval = base.multiplier;
    b.multipliers.lag.assign(cells, 0.0);
    const double nu = base_.bound_noise(o.holes);
    const std::vector<char> forbidden = forbidden_lags(n_, o.min_spacing_cells);
    if (nu > 0.0) {
        // Step scale: |mu|, or (mu = 0) the steepest slope a group has at x = 1.
        double scale = std::fabs(base.multiplier);
        if (!(scale > 0.0))
            for (int a = 1; a < cells; ++a) scale = std::max(scale, -base_.group_slope(a, 1.0, nu));
        const AutocorrDualOracle oracle = [&](const AutocorrMultipliers& m,
                                              std::vector<double>& x) {
            return evaluate(m, o.holes, nu, x);
        };
        const AutocorrAscent up = ascend_autocorr_dual(
            oracle, b.multipliers, n_, o.holes, forbidden, o.lags, kFirstStepFraction * scale,
            o.max_iterations, o.stall_iterations, o.stall_tolerance);
        b.iterations = up.iterations;
        if (up.value / big_n2 > base.mse) {
            b.mse = up.value / big_n2;
            b.multipliers = up.best;
            evaluate(b.multipliers, o.holes, nu, b.x);
        }
    }
    b.psnr_db = psnr_from_mse(b.mse);
    // Constraint violation of the minimisers (0 at a primal-feasible x: then mse is optimal).
    const std::vector<double> r = scaled_autocorrelation(n_, b.x);
    const double to_r = static_cast<double>(o.holes) * o.holes / cells;  // r = to_r * scaled
    double v = std::fabs(r[0] * to_r - o.holes);
    for (int d = 1; d < cells; ++d)
        v = std::max(v, forbidden[d] ? std::fabs(r[d] * to_r) : -r[d] * to_r);
    b.violation = v / o.holes;
    return b;
}

}  // namespace pinmask
