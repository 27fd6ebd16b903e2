#include "optimize/metrics/analytic_error.hpp"

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "optimize/metrics/nsr_tuning.hpp"
#include "optimize/simulate/image_quality.hpp"

namespace pinmask {
namespace {

std::string size_text(Eigen::Index r, Eigen::Index c) {
    return std::to_string(r) + " x " + std::to_string(c);
}

// The per-frequency sums take a fixed or optimal filter; kTunedNsr is a search over fixed ones.
void check_filter(const WienerFilterSpec& f) {
    if (f.kind == WienerFilterKind::kTunedNsr) {
        throw invalid_field("filter", "tuned",
                            "a tuned NSR is evaluated by AnalyticWienerModel (evaluate_tuned_nsr), "
                            "not per frequency");
    }
    if (f.kind == WienerFilterKind::kFixedNsr && (!(f.nsr > 0.0) || !std::isfinite(f.nsr))) {
        throw invalid_field("nsr", std::to_string(f.nsr), "must be finite and > 0");
    }
}

void check_variance(double v) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
        throw invalid_field("noise_variance", std::to_string(v), "must be finite and >= 0");
    }
}

// One frequency's contribution to N^2 MSE; n_sigma2 = N sigma^2.
inline double term(double h, double s, double n_sigma2, const WienerFilterSpec& f) {
    if (f.kind == WienerFilterKind::kFixedNsr) {
        const double d = h + f.nsr;
        return (f.nsr * f.nsr * s + h * n_sigma2) / (d * d);
    }
    const double d = h * s + n_sigma2;
    return d > 0.0 ? s * n_sigma2 / d : s;
}

// |P^|^2 / K^2, n x n.
Plane normalised_pattern_power(const ComplexPlane& p) {
    if (p.rows() < 1 || p.cols() != p.rows()) {
        throw InvalidInput("pattern spectrum is " + size_text(p.rows(), p.cols()) +
                           ": must be square n x n, n >= 1");
    }
    const double k = p(0, 0).real();
    if (!(k >= 0.5)) {
        throw InvalidInput("pattern spectrum: P^(0) = " + std::to_string(k) +
                           ": must be the pinhole count K >= 1");
    }
    return p.abs2() / (k * k);
}

Plane normalised_kernel_power(const ComplexPlane& kernel) {
    if (kernel.rows() < 1 || kernel.cols() != kernel.rows()) {
        throw InvalidInput("kernel OTF is " + size_text(kernel.rows(), kernel.cols()) +
                           ": must be square m x m, m >= 1");
    }
    const double k0 = std::norm(kernel(0, 0));
    if (!(k0 > 0.0) || !kernel.isFinite().all()) {
        throw InvalidInput(
            "kernel OTF: K^(0) = 0 or non-finite values: the kernel must have a "
            "non-zero sum");
    }
    return kernel.abs2() / k0;
}

}  // namespace

Plane mask_otf_power(const ComplexPlane& pattern_spectrum, const ComplexPlane& kernel_otf) {
    const Plane pp = normalised_pattern_power(pattern_spectrum);
    const Plane kp = normalised_kernel_power(kernel_otf);
    const Eigen::Index n = pp.rows(), m = kp.rows();
    if (m % n != 0) {
        throw InvalidInput("kernel OTF is " + size_text(m, m) +
                           ": its size must be a multiple of the pattern size " +
                           std::to_string(n));
    }
    Plane h(m, m);
    for (Eigen::Index k = 0; k < m; ++k)
        for (Eigen::Index l = 0; l < m; ++l) h(k, l) = pp(k % n, l % n) * kp(k, l);
    return h;
}

double expected_mean_square_capture(const Plane& h, const Plane& s) {
    if (h.rows() != s.rows() || h.cols() != s.cols() || h.size() == 0) {
        throw InvalidInput("OTF power is " + size_text(h.rows(), h.cols()) + ", prior is " +
                           size_text(s.rows(), s.cols()) + ": sizes must match");
    }
    const double n = static_cast<double>(h.size());
    return (h * s).sum() / (n * n);
}

double wiener_mse(const Plane& h, const Plane& s, double noise_variance,
                  const WienerFilterSpec& filter) {
    if (h.rows() != s.rows() || h.cols() != s.cols() || h.size() == 0) {
        throw InvalidInput("OTF power is " + size_text(h.rows(), h.cols()) + ", prior is " +
                           size_text(s.rows(), s.cols()) + ": sizes must match");
    }
    check_variance(noise_variance);
    check_filter(filter);
    const double n = static_cast<double>(h.size());
    double sum = 0.0;
    for (Eigen::Index i = 0; i < h.size(); ++i) {
        sum += term(h.data()[i], s.data()[i], n * noise_variance, filter);
    }
    return sum / (n * n);
}

AnalyticWienerModel::AnalyticWienerModel(const ComplexPlane& kernel_otf, ScenePrior prior,
                                         NoiseModel noise)
    : kernel_power_(normalised_kernel_power(kernel_otf)), prior_(std::move(prior)), noise_(noise) {
    validate(noise_);
    if (prior_.power.rows() != kernel_power_.rows() ||
        prior_.power.cols() != kernel_power_.cols()) {
        throw InvalidInput("scene prior is " + size_text(prior_.power.rows(), prior_.power.cols()) +
                           ", kernel OTF is " +
                           size_text(kernel_power_.rows(), kernel_power_.cols()) +
                           ": the prior must be estimated at the period size");
    }
}

Plane AnalyticWienerModel::pattern_power(const ComplexPlane& p) const {
    Plane pp = normalised_pattern_power(p);
    if (kernel_power_.rows() % pp.rows() != 0) {
        throw InvalidInput("pattern size " + std::to_string(pp.rows()) +
                           " does not divide the period " + std::to_string(kernel_power_.rows()));
    }
    return pp;
}

double AnalyticWienerModel::mean_square_of(const Plane& pp) const {
    const Eigen::Index n = pp.rows(), m = kernel_power_.rows();
    double sum = 0.0;
    for (Eigen::Index k = 0; k < m; ++k)
        for (Eigen::Index l = 0; l < m; ++l)
            sum += pp(k % n, l % n) * kernel_power_(k, l) * prior_.power(k, l);
    const double big_n = static_cast<double>(m * m);
    return sum / (big_n * big_n);
}

double AnalyticWienerModel::mse_of(const Plane& pp, double sigma2,
                                   const WienerFilterSpec& f) const {
    const Eigen::Index n = pp.rows(), m = kernel_power_.rows();
    const double big_n = static_cast<double>(m * m);
    double sum = 0.0;
    for (Eigen::Index k = 0; k < m; ++k)
        for (Eigen::Index l = 0; l < m; ++l)
            sum +=
                term(pp(k % n, l % n) * kernel_power_(k, l), prior_.power(k, l), big_n * sigma2, f);
    return sum / (big_n * big_n);
}

double AnalyticWienerModel::noise_variance(double mean_square, int open_cells,
                                           int total_cells) const {
    return mean_noise_variance(noise_, {prior_.mean, mean_square, open_cells, total_cells});
}

AnalyticError AnalyticWienerModel::evaluate(const ComplexPlane& p,
                                            const WienerFilterSpec& filter) const {
    if (filter.kind == WienerFilterKind::kTunedNsr) return evaluate_tuned_nsr(p);
    check_filter(filter);
    const Plane pp = pattern_power(p);
    AnalyticError e;
    e.mean_square_capture = mean_square_of(pp);
    const int open = static_cast<int>(std::lround(p(0, 0).real()));
    e.noise_variance = noise_variance(e.mean_square_capture, open, static_cast<int>(p.size()));
    e.mse = mse_of(pp, e.noise_variance, filter);
    e.psnr_db = psnr_from_mse(e.mse);
    e.nsr = filter.kind == WienerFilterKind::kFixedNsr ? filter.nsr : 0.0;
    return e;
}

AnalyticError AnalyticWienerModel::evaluate_tuned_nsr(const ComplexPlane& p) const {
    const Plane pp = pattern_power(p);
    AnalyticError e;
    e.mean_square_capture = mean_square_of(pp);
    const int open = static_cast<int>(std::lround(p(0, 0).real()));
    e.noise_variance = noise_variance(e.mean_square_capture, open, static_cast<int>(p.size()));
    const ScalarMinimum best = tune_log_weight([&](double nsr) {
        return mse_of(pp, e.noise_variance, {WienerFilterKind::kFixedNsr, nsr});
    });
    e.nsr = best.x;
    e.mse = best.value;
    e.psnr_db = psnr_from_mse(e.mse);
    return e;
}

}  // namespace pinmask
