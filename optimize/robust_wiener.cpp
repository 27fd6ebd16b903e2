#include "optimize/robust_wiener.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/fft.hpp"
#include "design/psf.hpp"
#include "optimize/image_quality.hpp"
#include "optimize/robust_sample.hpp"

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
    if (!errors_.any()) {
        errors_.validate(tmpl.camera.pinhole_m);
        return;
    }
    const JitterTransfer jt = jitter_transfer(jitter_sigma_px(tmpl, errors_), m);
    const double keep = 1.0 / (1.0 - errors_.missing);
    for (const Kernel& k : fabricated_kernels(tmpl, errors_)) {
        const ComplexPlane kappa_s = normalised_kernel_otf(k, n_, ppc);
        ComplexPlane cross(m, m);
        Plane var(m, m);
        for (int r = 0; r < m; ++r)
            for (int c = 0; c < m; ++c) {
                const std::complex<double> j = jt.mean[r] * jt.mean[c];
                const double b = jt.power[r] * jt.power[c];
                cross(r, c) = std::conj(kappa(r, c)) * kappa_s(r, c) * j;
                // B >= |J|^2 (Jensen); rounding may leave -1e-17: clip.
                var(r, c) = std::norm(kappa_s(r, c)) * std::max(0.0, b * keep - std::norm(j));
            }
        cross_.push_back(std::move(cross));
        variance_.push_back(std::move(var));
    }
}

double RobustWienerModel::robust_mse(const ComplexPlane& p, double sigma2,
                                     const WienerFilterSpec& f) const {
    const Plane& kp = nominal_->kernel_power();
    const Plane& s = nominal_->prior().power;
    const Eigen::Index m = kp.rows(), n = p.rows();
    const double holes = p(0, 0).real();
    const Plane pp = p.abs2() / (holes * holes);
    const double big_n = static_cast<double>(m * m), n_sigma2 = big_n * sigma2;
    double total = 0.0;
    for (std::size_t c = 0; c < cross_.size(); ++c) {
        const ComplexPlane& cross = cross_[c];
        const Plane& var = variance_[c];
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
                sum += std::norm(bias) * sk + w * w * h * (var(k, l) / holes * sk + n_sigma2);
            }
        total += sum;
    }
    return total / (static_cast<double>(cross_.size()) * big_n * big_n);
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
    r.mse = robust_mse(p, r.nominal.noise_variance, f);
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
    r.mse = robust_mse(p, r.nominal.noise_variance, {WienerFilterKind::kFixedNsr, r.nominal.nsr});
    r.psnr_db = psnr_from_mse(r.mse);
    return r;
}

RobustObjective::RobustObjective(ObjectiveWeights weights,
                                 std::shared_ptr<const RobustWienerModel> model,
                                 WienerFilterSpec filter)
    : weights_(weights), model_(std::move(model)), filter_(filter) {
    weights_.validate();
    if (!model_) throw InvalidInput("the robust objective needs a robust Wiener model");
    ObjectiveWeights others = weights_;
    others.analytic_wiener = 0.0;
    if (others.max_sidelobe > 0.0 || others.sidelobe_energy > 0.0 || others.min_spectrum > 0.0) {
        others_ = std::make_unique<MaskObjective>(others, nullptr, filter_);
    }
}

double RobustObjective::evaluate(const PatternState& s) const {
    double total = others_ ? others_->evaluate(s) : 0.0;
    if (weights_.analytic_wiener > 0.0) {
        total -= weights_.analytic_wiener * model_->evaluate(s.spectrum(), filter_).psnr_db;
    }
    return total;
}

std::map<std::string, double> RobustObjective::terms(const PatternState& s) const {
    std::map<std::string, double> out;
    if (others_) out = others_->terms(s);
    const RobustError e = model_->evaluate(s.spectrum(), filter_);
    out["analytic_wiener_psnr_db"] = e.nominal.psnr_db;
    out["analytic_wiener"] = -e.nominal.psnr_db;
    out["robust_wiener_psnr_db"] = e.psnr_db;
    out["robust_wiener"] = -e.psnr_db;
    out["objective"] = evaluate(s);
    return out;
}

}  // namespace pinmask
