#include "optimize/metrics/aliased_wiener.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "optimize/metrics/nsr_tuning.hpp"
#include "optimize/simulate/image_quality.hpp"

namespace pinmask {
namespace {

// The cubic Hermite weights of the two table points (values h00, h01) and their slopes in u
// (h10, h11, already times the step) at fraction f of the step.
struct HermiteWeights {
    double h00, h10, h01, h11;
};
inline HermiteWeights hermite_basis(double f, double step) {
    const double g = 1.0 - f;
    return {(1.0 + 2.0 * f) * g * g, f * g * g * step, f * f * (3.0 - 2.0 * f), -f * f * g * step};
}

// x below this (|P^| / K < 1e-3, next to a spectral zero) is summed exactly, never tabulated.
constexpr double kSmallestTabulatedX = 1e-6;
// Widest u range tabulated (e^48 ~ 7e20 in x / (N sigma^2)); beyond it the exact sum is used.
constexpr double kMaxRange = 48.0;
// Largest table kept (bytes); a larger pattern (n ~ 250 and up) keeps the exact O(m^2) sums.
constexpr double kMaxTableBytes = 256.0 * 1024 * 1024;
// Tuned NSR: largest table per grid NSR (n up to ~48). A search builds the NSRs its patterns tune
// to, a decade or two of the grid (32 per decade), so a few hundred MB at most; a larger pattern
// sums every frequency exactly at each grid NSR the descent visits.
constexpr double kMaxTunedTableBytes = 8.0 * 1024 * 1024;

}  // namespace

AliasedWiener::AliasedWiener(std::shared_ptr<const AnalyticWienerModel> model, int n,
                             const WienerFilterSpec& filter)
    : model_(std::move(model)), n_(n), filter_(filter) {
    if (!model_) throw InvalidInput("AliasedWiener: no analytic Wiener model");
    const int m = model_->period();
    if (n < 1 || m % n != 0) {
        throw InvalidInput("pattern size " + std::to_string(n) + " does not divide the period " +
                           std::to_string(m));
    }
    if (filter.kind == WienerFilterKind::kFixedNsr &&
        (!(filter.nsr > 0.0) || !std::isfinite(filter.nsr))) {
        throw invalid_field("nsr", std::to_string(filter.nsr), "must be finite and > 0");
    }
    p_ = m / n;
    const int cells = n * n, aliases = p_ * p_;
    const Plane& kp = model_->kernel_power();
    const Plane& s = model_->prior().power;
    capture_weight_.assign(cells, 0.0);
    kp_.resize(static_cast<std::size_t>(cells) * aliases);
    s_.resize(kp_.size());
    for (int ar = 0; ar < n; ++ar)
        for (int ac = 0; ac < n; ++ac) {
            const int a = ar * n + ac;
            std::size_t at = static_cast<std::size_t>(a) * aliases;
            for (int i = 0; i < p_; ++i)
                for (int j = 0; j < p_; ++j, ++at) {
                    kp_[at] = kp(ar + i * n, ac + j * n);
                    s_[at] = s(ar + i * n, ac + j * n);
                    capture_weight_[a] += kp_[at] * s_[at];
                }
        }
    if (filter.kind == WienerFilterKind::kFixedNsr) {
        width_ = 4;
        build_tables(std::log(kSmallestTabulatedX), step_);
        return;
    }
    if (filter.kind == WienerFilterKind::kTunedNsr) {
        width_ = 4;
        u0_ = std::log(kSmallestTabulatedX);
        const int points = static_cast<int>(std::ceil((step_ - u0_) / step_)) + 1;
        if (static_cast<double>(cells) * points * width_ * sizeof(double) <= kMaxTunedTableBytes)
            points_ = points;
        const int slots =
            static_cast<int>(std::lround((kTuneMaxLog10 - kTuneMinLog10) * kNsrGridPerDecade)) + 1;
        nsr_slots_.resize(static_cast<std::size_t>(slots));
        for (auto& slot : nsr_slots_) slot = std::make_unique<NsrSlot>();
        // Start of the descent: NSR = N sigma^2 / S-bar, S-bar the prior's power averaged over
        // the non-zero frequencies weighted by the kernel's (the per-frequency optimum is
        // N sigma^2 / S(k); only the number of descent steps depends on this choice).
        double weighted = 0.0, weights = 0.0;
        for (std::size_t i = 1; i < kp_.size(); ++i) {
            weighted += kp_[i] * s_[i];
            weights += kp_[i];
        }
        if (weighted > 0.0 && weights > 0.0) nsr_start_scale_ = weights / weighted;
        return;
    }
    // Noise variances over every K in 1..n^2 and every mean(c^2) a pattern can give
    // (x(0) = 1, 0 <= x <= 1 elsewhere).
    width_ = 2;
    const double big_n = static_cast<double>(m) * m;
    double total = 0.0;
    for (double c : capture_weight_) total += c;
    double nu_lo = INFINITY, nu_hi = 0.0;
    for (double ms : {capture_weight_[0] / (big_n * big_n), total / (big_n * big_n)})
        for (int open : {1, cells}) {
            const double nu = big_n * model_->noise_variance(ms, open, cells);
            nu_lo = std::min(nu_lo, nu);
            nu_hi = std::max(nu_hi, nu);
        }
    if (!(nu_lo > 0.0) || !std::isfinite(nu_hi)) return;  // noise-free: exact sums only
    const double u_hi = -std::log(nu_lo) + 0.5;
    const double u_lo = std::max(std::log(kSmallestTabulatedX / nu_hi) - 0.5, u_hi - kMaxRange);
    build_tables(u_lo, u_hi);
}

void AliasedWiener::build_tables(double u_lo, double u_hi) {
    const int cells = n_ * n_, aliases = p_ * p_;
    const int points = static_cast<int>(std::ceil((u_hi - u_lo) / step_)) + 1;
    if (static_cast<double>(cells) * points * width_ * sizeof(double) > kMaxTableBytes) return;
    points_ = points;
    u0_ = u_lo;
    if (width_ == 4) {
        table_ = fixed_nsr_table(filter_.nsr, u0_, points_);
        return;
    }
    table_.assign(static_cast<std::size_t>(cells) * points_ * width_, 0.0);
    for (int a = 0; a < cells; ++a) {
        const double* kp = kp_.data() + static_cast<std::size_t>(a) * aliases;
        const double* s = s_.data() + static_cast<std::size_t>(a) * aliases;
        for (int i = 0; i < points_; ++i) {
            const double e = std::exp(u0_ + i * step_);
            double* out = table_.data() + (static_cast<std::size_t>(a) * points_ + i) * width_;
            for (int j = 0; j < aliases; ++j) {  // optimal: s / (1 + e kp s), e = x / (N sigma^2)
                const double q = e * kp[j] * s[j], d = 1.0 + q;
                out[0] += s[j] / d;
                out[1] -= s[j] * q / (d * d);
            }
        }
    }
}

std::vector<double> AliasedWiener::fixed_nsr_table(double nsr, double u_lo, int points) const {
    const int cells = n_ * n_, aliases = p_ * p_;
    std::vector<double> table(static_cast<std::size_t>(cells) * points * 4, 0.0);
    for (int a = 0; a < cells; ++a) {
        const double* kp = kp_.data() + static_cast<std::size_t>(a) * aliases;
        const double* s = s_.data() + static_cast<std::size_t>(a) * aliases;
        for (int i = 0; i < points; ++i) {
            const double e = std::exp(u_lo + i * step_);  // e = x, h = x kp
            double* out = table.data() + (static_cast<std::size_t>(a) * points + i) * 4;
            for (int j = 0; j < aliases; ++j) {
                const double h = e * kp[j], d = h + nsr, d2 = d * d, d3 = d2 * d;
                out[0] += nsr * nsr * s[j] / d2;
                out[1] -= 2.0 * nsr * nsr * s[j] * h / d3;
                out[2] += h / d2;
                out[3] += h * (nsr - h) / d3;
            }
        }
    }
    return table;
}

// The per-frequency terms of optimize/metrics/analytic_error.cpp, summed over the aliases of a.
double AliasedWiener::exact_sum(int a, double x, double n_sigma2, double nsr) const {
    const int aliases = p_ * p_;
    const double* kp = kp_.data() + static_cast<std::size_t>(a) * aliases;
    const double* s = s_.data() + static_cast<std::size_t>(a) * aliases;
    double sum = 0.0;
    for (int j = 0; j < aliases; ++j) {
        const double h = x * kp[j];
        if (filter_.kind != WienerFilterKind::kOptimal) {
            const double d = h + nsr;
            sum += (nsr * nsr * s[j] + h * n_sigma2) / (d * d);
        } else {
            const double d = h * s[j] + n_sigma2;
            sum += d > 0.0 ? s[j] * n_sigma2 / d : s[j];
        }
    }
    return sum;
}

AnalyticError AliasedWiener::evaluate(const ComplexPlane& p) const {
    if (p.rows() != n_ || p.cols() != n_) {
        throw InvalidInput("pattern spectrum is " + std::to_string(p.rows()) + " x " +
                           std::to_string(p.cols()) + ": the aliased model was built for " +
                           std::to_string(n_) + " x " + std::to_string(n_));
    }
    const double k = p(0, 0).real();
    if (!(k >= 0.5)) {
        throw InvalidInput("pattern spectrum: P^(0) = " + std::to_string(k) +
                           ": must be the pinhole count K >= 1");
    }
    if (filter_.kind == WienerFilterKind::kTunedNsr) return evaluate_tuned(p);
    const double m = static_cast<double>(n_) * p_, big_n = m * m, inv_k2 = 1.0 / (k * k);
    double ms = 0.0;
    for (int ar = 0; ar < n_; ++ar)
        for (int ac = 0; ac < n_; ++ac)
            ms += std::norm(p(ar, ac)) * inv_k2 * capture_weight_[ar * n_ + ac];
    AnalyticError e;
    e.mean_square_capture = ms / (big_n * big_n);
    const int open = static_cast<int>(std::lround(k));
    e.noise_variance = model_->noise_variance(e.mean_square_capture, open, n_ * n_);
    const double nu = big_n * e.noise_variance;
    const bool optimal = filter_.kind == WienerFilterKind::kOptimal;
    const double u_end = u0_ + (points_ - 1) * step_, inv_step = 1.0 / step_;
    const double log_nu = optimal ? std::log(nu) : 0.0;
    double sum = 0.0;
    for (int ar = 0; ar < n_; ++ar)
        for (int ac = 0; ac < n_; ++ac) {
            const int a = ar * n_ + ac;
            const double x = std::norm(p(ar, ac)) * inv_k2;
            const double u = x > 0.0 ? std::log(x) - log_nu : -INFINITY;
            if (!(points_ > 1 && u >= u0_ && u < u_end)) {
                sum += exact_sum(a, x, nu, filter_.nsr);
                continue;
            }
            const double t = (u - u0_) * inv_step;
            const int i = static_cast<int>(t);
            const auto [h00, h10, h01, h11] = hermite_basis(t - i, step_);
            const double* r = table_.data() + (static_cast<std::size_t>(a) * points_ + i) * width_;
            const double* q = r + width_;
            sum += h00 * r[0] + h10 * r[1] + h01 * q[0] + h11 * q[1];
            if (!optimal) sum += nu * (h00 * r[2] + h10 * r[3] + h01 * q[2] + h11 * q[3]);
        }
    e.mse = sum / (big_n * big_n);
    e.psnr_db = psnr_from_mse(e.mse);
    e.nsr = optimal ? 0.0 : filter_.nsr;
    return e;
}

double AliasedWiener::fixed_nsr_sum(int index, const std::vector<double>& x, double nu) const {
    const double nsr =
        std::pow(10.0, kTuneMinLog10 + static_cast<double>(index) / kNsrGridPerDecade);
    NsrSlot& slot = *nsr_slots_[static_cast<std::size_t>(index)];
    if (points_ > 1)
        std::call_once(slot.once, [&] { slot.table = fixed_nsr_table(nsr, u0_, points_); });
    const double u_end = u0_ + (points_ - 1) * step_, inv_step = 1.0 / step_;
    double sum = 0.0;
    for (int a = 0; a < n_ * n_; ++a) {
        const double xa = x[static_cast<std::size_t>(a)];
        const double u = xa > 0.0 ? std::log(xa) : -INFINITY;
        if (!(points_ > 1 && u >= u0_ && u < u_end)) {
            sum += exact_sum(a, xa, nu, nsr);
            continue;
        }
        const double t = (u - u0_) * inv_step;
        const int i = static_cast<int>(t);
        const auto [h00, h10, h01, h11] = hermite_basis(t - i, step_);
        const double* r = slot.table.data() + (static_cast<std::size_t>(a) * points_ + i) * 4;
        const double* q = r + 4;
        sum += h00 * r[0] + h10 * r[1] + h01 * q[0] + h11 * q[1];
        sum += nu * (h00 * r[2] + h10 * r[3] + h01 * q[2] + h11 * q[3]);
    }
    return sum;
}

AnalyticError AliasedWiener::evaluate_tuned(const ComplexPlane& p) const {
    const double k = p(0, 0).real();
    const double m = static_cast<double>(n_) * p_, big_n = m * m, inv_k2 = 1.0 / (k * k);
    std::vector<double> x(static_cast<std::size_t>(n_) * n_);
    double ms = 0.0;
    for (int ar = 0; ar < n_; ++ar)
        for (int ac = 0; ac < n_; ++ac) {
            const int a = ar * n_ + ac;
            x[static_cast<std::size_t>(a)] = std::norm(p(ar, ac)) * inv_k2;
            ms += x[static_cast<std::size_t>(a)] * capture_weight_[a];
        }
    AnalyticError e;
    e.mean_square_capture = ms / (big_n * big_n);
    const int open = static_cast<int>(std::lround(k));
    e.noise_variance = model_->noise_variance(e.mean_square_capture, open, n_ * n_);
    const double nu = big_n * e.noise_variance;

    // Descent on the NSR grid (strict improvement only), then the parabola through the minimum.
    const int last = static_cast<int>(nsr_slots_.size()) - 1;
    const double start = nu > 0.0 ? std::log10(nu * nsr_start_scale_) : kTuneMinLog10;
    int j = std::clamp(static_cast<int>(std::lround((start - kTuneMinLog10) * kNsrGridPerDecade)),
                       0, last);
    auto f = [&](int i) { return fixed_nsr_sum(i, x, nu); };
    double fj = f(j);
    double up = j < last ? f(j + 1) : INFINITY;
    double down = INFINITY;
    if (up < fj) {
        down = fj;
        ++j, fj = up;
        up = j < last ? f(j + 1) : INFINITY;
        while (up < fj) {
            down = fj;
            ++j, fj = up;
            up = j < last ? f(j + 1) : INFINITY;
        }
    } else {
        down = j > 0 ? f(j - 1) : INFINITY;
        while (down < fj) {
            up = fj;
            --j, fj = down;
            down = j > 0 ? f(j - 1) : INFINITY;
        }
    }
    double offset = 0.0, best = fj;
    const double curvature = down - 2.0 * fj + up;
    if (std::isfinite(curvature) && curvature > 0.0) {
        offset = 0.5 * (down - up) / curvature;  // |offset| <= 1/2: fj is the grid minimum
        best = fj - 0.25 * (down - up) * offset;
    }
    e.mse = best / (big_n * big_n);
    e.psnr_db = psnr_from_mse(e.mse);
    e.nsr = std::pow(10.0, kTuneMinLog10 + (j + offset) / kNsrGridPerDecade);
    return e;
}

}  // namespace pinmask
