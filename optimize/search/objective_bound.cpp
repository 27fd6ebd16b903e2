#include "optimize/search/objective_bound.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/errors/error.hpp"
#include "optimize/simulate/image_quality.hpp"

namespace pinmask {
namespace {

// Newton steps per inner root (monotone from the left; converges in well under 60).
constexpr int kMaxNewtonSteps = 60;
// Inner root: stop when the Newton step is below this (x is in [0, 1]).
constexpr double kNewtonStepTol = 1e-15;

}  // namespace

void ObjectiveBoundOptions::validate(int cells) const {
    if (holes < 1 || holes > cells) {
        throw invalid_field("holes", std::to_string(holes),
                            "must be in 1.." + std::to_string(cells) + " (the pattern's cells)");
    }
    if (!(sum_tolerance > 0.0) || !(sum_tolerance < 1.0)) {
        throw invalid_field("sum_tolerance", std::to_string(sum_tolerance), "must be in (0, 1)");
    }
    if (max_iterations < 1 || max_iterations > 10000) {
        throw invalid_field("max_iterations", std::to_string(max_iterations),
                            "must be in 1..10000");
    }
}

ObjectiveBoundModel::ObjectiveBoundModel(std::shared_ptr<const AnalyticWienerModel> model, int n)
    : model_(std::move(model)), n_(n) {
    if (!model_) throw InvalidInput("ObjectiveBoundModel: no analytic Wiener model");
    const int m = model_->period();
    if (n < 1 || m % n != 0) {
        throw InvalidInput("pattern size " + std::to_string(n) + " does not divide the period " +
                           std::to_string(m));
    }
    p_ = m / n;
    const int cells = n * n;
    const Plane& kp = model_->kernel_power();
    const Plane& s = model_->prior().power;
    blind_.assign(cells, 0.0);
    capture_weight_.assign(cells, 0.0);
    start_.assign(cells + 1, 0);
    for (int ar = 0; ar < n; ++ar)
        for (int ac = 0; ac < n; ++ac) {
            const int a = ar * n + ac;
            start_[a] = s_.size();
            for (int i = 0; i < p_; ++i)
                for (int j = 0; j < p_; ++j) {
                    const double sj = s(ar + i * n, ac + j * n);
                    const double c = kp(ar + i * n, ac + j * n) * sj;
                    capture_weight_[a] += c;
                    if (c > 0.0) {
                        s_.push_back(sj);
                        c_.push_back(c);
                    } else {
                        blind_[a] += sj;
                    }
                }
        }
    start_[cells] = s_.size();
}

double ObjectiveBoundModel::group_error(int a, double x, double nu) const {
    double sum = blind_[a];
    for (std::size_t j = start_[a]; j < start_[a + 1]; ++j) {
        const double d = x * c_[j] + nu;
        sum += d > 0.0 ? s_[j] * nu / d : s_[j];
    }
    return sum;
}

double ObjectiveBoundModel::group_slope(int a, double x, double nu) const {
    double sum = 0.0;
    for (std::size_t j = start_[a]; j < start_[a + 1]; ++j) {
        const double d = x * c_[j] + nu;
        sum -= s_[j] * c_[j] * nu / (d * d);
    }
    return sum;
}

double ObjectiveBoundModel::bound_noise(int holes) const {
    const int cells = n_ * n_;
    // Smallest mean(c^2) of the relaxed set: x(0) = 1, the rest X = n^2/K - 1 in [0, 1] each,
    // placed on the smallest C(a) first.
    std::vector<double> c(capture_weight_.begin() + 1, capture_weight_.end());
    std::sort(c.begin(), c.end());
    double left = static_cast<double>(cells) / holes - 1.0, ms = capture_weight_[0];
    for (double w : c) {
        if (!(left > 0.0)) break;
        const double take = std::min(1.0, left);
        ms += take * w;
        left -= take;
    }
    const double big_n = static_cast<double>(model_->period()) * model_->period();
    return big_n * model_->noise_variance(ms / (big_n * big_n), holes, cells);
}

double ObjectiveBoundModel::solve_group(int a, double mu, double nu) const {
    // phi(x) = -g_a'(x) is decreasing and convex: Newton from x = 0 stays left of the root.
    if (-group_slope(a, 0.0, nu) <= mu) return 0.0;
    if (-group_slope(a, 1.0, nu) >= mu) return 1.0;
    double x = 0.0;
    for (int it = 0; it < kMaxNewtonSteps; ++it) {
        double phi = 0.0, dphi = 0.0;
        for (std::size_t j = start_[a]; j < start_[a + 1]; ++j) {
            const double d = x * c_[j] + nu, t = s_[j] * c_[j] * nu / (d * d);
            phi += t;
            dphi -= 2.0 * t * c_[j] / d;
        }
        if (!(dphi < 0.0)) break;
        const double step = (phi - mu) / -dphi;
        if (!(step > 0.0)) break;
        x = std::min(1.0, x + step);
        if (step < kNewtonStepTol) break;
    }
    return x;
}

ObjectiveBound ObjectiveBoundModel::bound(const ObjectiveBoundOptions& o) const {
    const int cells = n_ * n_;
    o.validate(cells);
    const double big_n = static_cast<double>(model_->period()) * model_->period();
    ObjectiveBound b;
    b.holes = o.holes;
    const double nu = bound_noise(o.holes);
    b.noise_variance = nu / big_n;
    b.x.assign(cells, 0.0);
    b.x[0] = 1.0;
    const double target = static_cast<double>(cells) / o.holes - 1.0;

    const auto finish = [&](double dual) {
        double primal = group_error(0, 1.0, nu);
        for (int a = 1; a < cells; ++a) primal += group_error(a, b.x[a], nu);
        b.relaxed_mse = primal / (big_n * big_n);
        b.mse = std::min(dual, primal) / (big_n * big_n);
        b.psnr_db = psnr_from_mse(b.mse);
        return b;
    };

    // Noise-free: any x > 0 removes every error the kernel passes.
    if (!(nu > 0.0)) {
        double dual = 0.0;
        for (int a = 0; a < cells; ++a) dual += blind_[a];
        if (target > 0.0) {
            const double share = std::min(1.0, target / std::max(1, cells - 1));
            for (int a = 1; a < cells; ++a) b.x[a] = share;
        }
        // With K = n^2 every x(a != 0) is 0: those groups keep their full error.
        if (!(target > 0.0))
            for (int a = 1; a < cells; ++a) dual += group_error(a, 0.0, nu) - blind_[a];
        return finish(dual);
    }

    // mu -> 0: every group that sees light takes x = 1. If that fits, the sum is not active.
    int lit = 0;
    double mu_lo = INFINITY, mu_hi = 0.0;
    for (int a = 1; a < cells; ++a) {
        if (start_[a + 1] == start_[a]) continue;
        ++lit;
        mu_lo = std::min(mu_lo, -group_slope(a, 1.0, nu));
        mu_hi = std::max(mu_hi, -group_slope(a, 0.0, nu));
    }
    if (lit <= target) {
        for (int a = 1; a < cells; ++a) b.x[a] = start_[a + 1] > start_[a] ? 1.0 : 0.0;
        double dual = group_error(0, 1.0, nu);
        for (int a = 1; a < cells; ++a) dual += group_error(a, b.x[a], nu);
        return finish(dual);
    }
    // total(mu) = sum x_a(mu) is non-increasing: lit at mu_lo (> target), 0 at mu_hi.
    const auto total_at = [&](double mu) {
        double t = 0.0;
        for (int a = 1; a < cells; ++a) {
            b.x[a] = solve_group(a, mu, nu);
            t += b.x[a];
        }
        return t;
    };
    double lo = std::log(mu_lo), hi = std::log(mu_hi), mu = mu_hi;
    if (!(target > 0.0)) {
        for (int a = 1; a < cells; ++a) b.x[a] = 0.0;
    } else {
        for (b.iterations = 0; b.iterations < o.max_iterations; ++b.iterations) {
            const double mid = 0.5 * (lo + hi);
            mu = std::exp(mid);
            const double t = total_at(mu);
            if (std::fabs(t - target) <= o.sum_tolerance * cells || !(mid > lo && mid < hi)) break;
            (t > target ? lo : hi) = mid;
        }
    }
    b.multiplier = mu;
    // D(mu): each inner minimum bounded below by its tangent at the computed x (convexity).
    double dual = group_error(0, 1.0, nu) - mu * target;
    for (int a = 1; a < cells; ++a) {
        const double xa = b.x[a];
        const double slope = group_slope(a, xa, nu) + mu;
        dual += group_error(a, xa, nu) + mu * xa + std::min(-slope * xa, slope * (1.0 - xa));
    }
    return finish(dual);
}

}  // namespace pinmask
