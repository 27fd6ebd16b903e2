#include "optimize/metrics/robust_wiener.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/wiener.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/robust_sample.hpp"
#include "optimize/simulate/image_quality.hpp"

namespace pinmask {
namespace {

// K^ / K^(0) on the full m x m period.
ComplexPlane normalised_kernel_otf(const Kernel& kernel, int n, int ppc) {
    ComplexPlane k = expand_half_spectrum(kernel_spectrum(kernel, n, ppc), n * ppc);
    const std::complex<double> k0 = k(0, 0);
    if (!(std::abs(k0) > 0.0)) throw InvalidInput("fabricated kernel: K^(0) = 0");
    return k / k0;
}

}  // namespace

RobustWienerModel::RobustWienerModel(const Mask& tmpl, FabricationErrors errors, ScenePrior prior,
                                     NoiseModel noise)
    : errors_(errors), n_(tmpl.pattern.n) {
    const int ppc = tmpl.psf.pixels_per_cell, m = n_ * ppc;
    check_psf_memory(n_, ppc, 8, 2);
    const ComplexPlane kappa = normalised_kernel_otf(mask_kernel(tmpl), n_, ppc);
    nominal_ = std::make_shared<AnalyticWienerModel>(kappa, std::move(prior), noise);
    kappa_ = kappa;
    // Without errors the expected PSF is the nominal one and nothing varies.
    std::vector<ComplexPlane> truth{kappa};  // per bias sign: kappa_s J
    std::vector<Plane> var{Plane::Zero(m, m)};
    if (!errors_.any()) {
        errors_.validate(tmpl.camera.pinhole_m);
    } else {
        truth.clear();
        var.clear();
        const JitterTransfer jt = jitter_transfer(jitter_sigma_px(tmpl, errors_), m);
        const double keep = 1.0 / (1.0 - errors_.missing);
        for (const Kernel& k : fabricated_kernels(tmpl, errors_)) {
            const ComplexPlane kappa_s = normalised_kernel_otf(k, n_, ppc);
            ComplexPlane cross(m, m), t(m, m);
            Plane v(m, m);
            for (int r = 0; r < m; ++r)
                for (int c = 0; c < m; ++c) {
                    const std::complex<double> j = jt.mean[r] * jt.mean[c];
                    const double b = jt.power[r] * jt.power[c];
                    cross(r, c) = std::conj(kappa(r, c)) * kappa_s(r, c) * j;
                    t(r, c) = kappa_s(r, c) * j;
                    // B >= |J|^2 (Jensen); rounding may leave -1e-17: clip.
                    v(r, c) = std::norm(kappa_s(r, c)) * std::max(0.0, b * keep - std::norm(j));
                }
            cross_.push_back(std::move(cross));
            truth.push_back(std::move(t));
            var.push_back(std::move(v));
        }
    }
    const double cases = static_cast<double>(truth.size());
    expected_ = ComplexPlane::Zero(m, m);
    fabricated_power_ = Plane::Zero(m, m);
    mean_variance_ = Plane::Zero(m, m);
    for (std::size_t c = 0; c < truth.size(); ++c) {
        expected_ += truth[c] / cases;
        fabricated_power_ += truth[c].abs2() / cases;
        mean_variance_ += var[c] / cases;
    }
    expected_power_ = expected_.abs2();
    expected_nominal_cross_ = expected_.conjugate() * kappa;
    transfers_ = std::move(truth);
    variance_ = std::move(var);
    // The floor's ratio |E kappa_s|^2 / E|kappa_s|^2 equals |D|^2 / E|kappa_s J|^2 (J cancels).
    const Plane& s = nominal_->prior().power;
    double floor = 0.0;
    for (int r = 0; r < m; ++r)
        for (int c = 0; c < m; ++c) {
            const double e2 = fabricated_power_(r, c);
            const double ratio = e2 > 0.0 ? std::min(1.0, expected_power_(r, c) / e2) : 0.0;
            floor += s(r, c) * (1.0 - ratio);
        }
    const double big_n = static_cast<double>(m) * m;
    floor_mse_ = floor / (big_n * big_n);
}

double RobustWienerModel::mismatch_mse(const ComplexPlane& p, double sigma2,
                                       const WienerFilterSpec& f, const Plane& kp,
                                       const std::vector<ComplexPlane>& crosses,
                                       const std::vector<Plane>& variances) const {
    const Plane& s = nominal_->prior().power;
    const Eigen::Index m = kp.rows(), n = p.rows();
    const auto period = [m](const auto& plane) { return plane.rows() == m && plane.cols() == m; };
    bool sizes = m == s.rows() && period(kp) && !crosses.empty() &&
                 (variances.empty() || variances.size() == crosses.size()) &&
                 f.kind != WienerFilterKind::kTunedNsr;
    for (const ComplexPlane& c : crosses) sizes = sizes && period(c);
    for (const Plane& v : variances) sizes = sizes && period(v);
    if (!sizes) {
        throw InvalidInput(
            "robust mismatch error: decoder power, crosses and variances must be "
            "m x m, one variance per cross (or none), the filter fixed or optimal");
    }
    const double holes = p(0, 0).real();
    const Plane pp = p.abs2() / (holes * holes);
    const double big_n = static_cast<double>(m * m), n_sigma2 = big_n * sigma2;
    double total = 0.0;
    for (std::size_t c = 0; c < crosses.size(); ++c) {
        const ComplexPlane& cross = crosses[c];
        const Plane* var = variances.empty() ? nullptr : &variances[c];
        double sum = 0.0;
        for (Eigen::Index l = 0, ln = 0; l < m; ++l, ln = ln + 1 == n ? 0 : ln + 1)
            for (Eigen::Index k = 0, kn = 0; k < m; ++k, kn = kn + 1 == n ? 0 : kn + 1) {
                const double ppk = pp(kn, ln), h = ppk * kp(k, l), sk = s(k, l);
                double w;
                if (f.kind == WienerFilterKind::kFixedNsr) {
                    w = 1.0 / (h + f.nsr);
                } else {
                    const double d = h * sk + n_sigma2;
                    w = d > 0.0 ? sk / d : 0.0;
                }
                const std::complex<double> bias = w * ppk * cross(k, l) - 1.0;
                const double v = var ? (*var)(k, l) / holes * sk : 0.0;
                sum += std::norm(bias) * sk + w * w * h * (v + n_sigma2);
            }
        total += sum;
    }
    return total / (static_cast<double>(crosses.size()) * big_n * big_n);
}

RobustError RobustWienerModel::evaluate(const ComplexPlane& p, const WienerFilterSpec& f) const {
    if (f.kind == WienerFilterKind::kTunedNsr) return evaluate_tuned_nsr(p);
    RobustError r;
    r.nominal = nominal_->evaluate(p, f);
    if (cross_.empty()) {
        r.mse = r.nominal.mse;
        r.psnr_db = r.nominal.psnr_db;
        return r;
    }
    r.mse =
        mismatch_mse(p, r.nominal.noise_variance, f, nominal_->kernel_power(), cross_, variance_);
    r.psnr_db = psnr_from_mse(r.mse);
    return r;
}

RobustError RobustWienerModel::evaluate_tuned_nsr(const ComplexPlane& p) const {
    RobustError r;
    r.nominal = nominal_->evaluate_tuned_nsr(p);
    if (cross_.empty()) {
        r.mse = r.nominal.mse;
        r.psnr_db = r.nominal.psnr_db;
        return r;
    }
    r.mse = mismatch_mse(p, r.nominal.noise_variance, {WienerFilterKind::kFixedNsr, r.nominal.nsr},
                         nominal_->kernel_power(), cross_, variance_);
    r.psnr_db = psnr_from_mse(r.mse);
    return r;
}

RobustError RobustWienerModel::evaluate_robust_filter(const ComplexPlane& p) const {
    RobustError r;
    r.nominal = nominal_->evaluate(p, {WienerFilterKind::kOptimal, 0.0});
    const Plane& s = nominal_->prior().power;
    const Plane& kp = nominal_->kernel_power();
    const Eigen::Index m = kp.rows(), n = p.rows();
    const double holes = p(0, 0).real();
    const Plane pp = p.abs2() / (holes * holes);
    const double big_n = static_cast<double>(m * m);
    const double n_sigma2 = big_n * r.nominal.noise_variance;
    const ComplexPlane& kappa_cross = expected_nominal_cross_;  // conj(D) kappa
    double fab = 0.0, nom = 0.0;
    for (Eigen::Index l = 0, ln = 0; l < m; ++l, ln = ln + 1 == n ? 0 : ln + 1)
        for (Eigen::Index k = 0, kn = 0; k < m; ++k, kn = kn + 1 == n ? 0 : kn + 1) {
            const double ppk = pp(kn, ln), sk = s(k, l);
            const double et2 = ppk * fabricated_power_(k, l) + mean_variance_(k, l) / holes;
            const double mean2 = ppk * expected_power_(k, l);  // |E T|^2
            const double d = et2 * sk + n_sigma2;
            if (!(d > 0.0)) {
                fab += sk;
                nom += sk;
                continue;
            }
            fab += sk * ((et2 - mean2) * sk + n_sigma2) / d;
            // Nominal capture: G H = pp conj(D) kappa S / d, |G|^2 = |E T|^2 S^2 / d^2.
            const std::complex<double> gh = ppk * kappa_cross(k, l) * (sk / d);
            nom += std::norm(gh - 1.0) * sk + mean2 * sk * sk / (d * d) * n_sigma2;
        }
    r.nominal.mse = nom / (big_n * big_n);
    r.nominal.psnr_db = psnr_from_mse(r.nominal.mse);
    r.nominal.nsr = 0.0;
    r.mse = fab / (big_n * big_n);
    r.psnr_db = psnr_from_mse(r.mse);
    return r;
}

double RobustWienerModel::pattern_independent_floor_mse() const { return floor_mse_; }

RobustWienerModel::RobustTerms RobustWienerModel::robust_terms(const ComplexPlane& p) const {
    const AnalyticError nominal = nominal_->evaluate(p, {WienerFilterKind::kOptimal, 0.0});
    const Eigen::Index m = nominal_->prior().power.rows(), n = p.rows();
    const double holes = p(0, 0).real();
    RobustTerms t;
    t.n_sigma2 = static_cast<double>(m * m) * nominal.noise_variance;
    t.mean.resize(m, m);
    t.power.resize(m, m);
    for (Eigen::Index l = 0, ln = 0; l < m; ++l, ln = ln + 1 == n ? 0 : ln + 1)
        for (Eigen::Index k = 0, kn = 0; k < m; ++k, kn = kn + 1 == n ? 0 : kn + 1) {
            t.mean(k, l) = p(kn, ln) / holes * expected_(k, l);
            const double ppk = std::norm(p(kn, ln)) / (holes * holes);
            t.power(k, l) = ppk * fabricated_power_(k, l) + mean_variance_(k, l) / holes;
        }
    return t;
}

ComplexPlane RobustWienerModel::robust_filter_response(const ComplexPlane& p) const {
    const RobustTerms t = robust_terms(p);
    const Plane& s = nominal_->prior().power;
    const Eigen::Index m = s.rows();
    ComplexPlane g(m, m);
    for (Eigen::Index l = 0; l < m; ++l)
        for (Eigen::Index k = 0; k < m; ++k) {
            const double sk = s(k, l), d = t.power(k, l) * sk + t.n_sigma2;
            g(k, l) = d > 0.0 ? std::conj(t.mean(k, l)) * (sk / d) : 0.0;
        }
    return g;
}

RobustDecoderInputs RobustWienerModel::robust_decoder_inputs(const ComplexPlane& p) const {
    const RobustTerms t = robust_terms(p);
    const Plane& s = nominal_->prior().power;
    const Eigen::Index m = s.rows();
    RobustDecoderInputs out;
    out.nsr.resize(m, m);
    for (Eigen::Index l = 0; l < m; ++l)
        for (Eigen::Index k = 0; k < m; ++k) {
            const double sk = s(k, l), mean2 = std::norm(t.mean(k, l));
            // E|T|^2 >= |E T|^2 (Jensen); rounding may leave -1e-17: clip.
            const double variance = std::max(0.0, t.power(k, l) - mean2);
            out.nsr(k, l) = sk > 0.0 ? variance + t.n_sigma2 / sk : kRobustNsrNoSignal;
            if (mean2 + out.nsr(k, l) < kDeconvwnrDenominatorFloor) ++out.floored;
        }
    const FftC2 fft(static_cast<int>(m), static_cast<int>(m));
    out.psf = fft.inverse(t.mean).real();
    return out;
}

ComplexPlane RobustWienerModel::filter_response(const ComplexPlane& p,
                                                const WienerFilterSpec& f) const {
    WienerFilterSpec spec = f;
    if (f.kind == WienerFilterKind::kTunedNsr) {
        spec = {WienerFilterKind::kFixedNsr, evaluate_tuned_nsr(p).nominal.nsr};
    }
    return filter_response(p, spec, kappa_);
}

ComplexPlane RobustWienerModel::filter_response(const ComplexPlane& p, const WienerFilterSpec& spec,
                                                const ComplexPlane& decoder) const {
    if (spec.kind == WienerFilterKind::kTunedNsr) {
        throw InvalidInput("a decoder's filter response needs a fixed NSR or the optimal filter");
    }
    const AnalyticError nominal = nominal_->evaluate(p, {WienerFilterKind::kOptimal, 0.0});
    if (spec.kind == WienerFilterKind::kFixedNsr && (!(spec.nsr > 0.0) || !std::isfinite(spec.nsr)))
        throw invalid_field("nsr", std::to_string(spec.nsr), "must be finite and > 0");
    const Plane& s = nominal_->prior().power;
    const Eigen::Index m = s.rows(), n = p.rows();
    if (decoder.rows() != m || decoder.cols() != m) {
        throw InvalidInput("filter response: the decoder OTF is " + std::to_string(decoder.rows()) +
                           " x " + std::to_string(decoder.cols()) + ", the period " +
                           std::to_string(m));
    }
    const double holes = p(0, 0).real();
    const double n_sigma2 = static_cast<double>(m * m) * nominal.noise_variance;
    ComplexPlane g(m, m);
    for (Eigen::Index l = 0, ln = 0; l < m; ++l, ln = ln + 1 == n ? 0 : ln + 1)
        for (Eigen::Index k = 0, kn = 0; k < m; ++k, kn = kn + 1 == n ? 0 : kn + 1) {
            const std::complex<double> h = p(kn, ln) / holes * decoder(k, l);
            const double h2 = std::norm(h), sk = s(k, l);
            double w;
            if (spec.kind == WienerFilterKind::kFixedNsr) {
                w = 1.0 / (h2 + spec.nsr);
            } else {
                const double d = h2 * sk + n_sigma2;
                w = d > 0.0 ? sk / d : 0.0;
            }
            g(k, l) = std::conj(h) * w;
        }
    return g;
}

}  // namespace pinmask
