#include "tests/research/expected_psf_decoder.hpp"

#include <vector>

#include "optimize/metrics/nsr_tuning.hpp"
#include "optimize/simulate/image_quality.hpp"

namespace pinmask {
namespace {

// conj(D) kappa: the nominal capture's cross term for the decoder D.
std::vector<ComplexPlane> nominal_cross(const RobustWienerModel& model) {
    return {model.expected_transfer().conjugate() * model.kernel_otf()};
}

// The tuned NSR for the nominal capture decoded with D (noise variance sigma2).
double tune_expected_psf_nsr(const RobustWienerModel& model, const ComplexPlane& p, double sigma2) {
    const Plane power = model.expected_transfer().abs2();
    const std::vector<ComplexPlane> cross = nominal_cross(model);
    return tune_log_weight([&](double nsr) {
               return model.mismatch_mse(p, sigma2, {WienerFilterKind::kFixedNsr, nsr}, power,
                                         cross, {});
           })
        .x;
}

}  // namespace

RobustError evaluate_expected_psf(const RobustWienerModel& model, const ComplexPlane& p,
                                  const WienerFilterSpec& f) {
    if (f.kind == WienerFilterKind::kTunedNsr) return evaluate_expected_psf_tuned_nsr(model, p);
    RobustError r;
    r.nominal = model.nominal().evaluate(p, f);
    if (!model.errors().any()) {
        r.mse = r.nominal.mse;
        r.psnr_db = r.nominal.psnr_db;
        return r;
    }
    const ComplexPlane& d = model.expected_transfer();
    const Plane power = d.abs2();
    std::vector<ComplexPlane> cross;
    for (const ComplexPlane& t : model.fabricated_transfers()) cross.push_back(d.conjugate() * t);
    const double sigma2 = r.nominal.noise_variance;
    r.nominal.mse = model.mismatch_mse(p, sigma2, f, power, nominal_cross(model), {});
    r.nominal.psnr_db = psnr_from_mse(r.nominal.mse);
    r.mse = model.mismatch_mse(p, sigma2, f, power, cross, model.fabricated_variances());
    r.psnr_db = psnr_from_mse(r.mse);
    return r;
}

RobustError evaluate_expected_psf_tuned_nsr(const RobustWienerModel& model, const ComplexPlane& p) {
    const AnalyticError tuned = model.nominal().evaluate_tuned_nsr(p);
    if (!model.errors().any()) {
        RobustError r;
        r.nominal = tuned;
        r.mse = r.nominal.mse;
        r.psnr_db = r.nominal.psnr_db;
        return r;
    }
    const double nsr = tune_expected_psf_nsr(model, p, tuned.noise_variance);
    RobustError r = evaluate_expected_psf(model, p, {WienerFilterKind::kFixedNsr, nsr});
    r.nominal.nsr = nsr;
    return r;
}

ComplexPlane expected_psf_filter_response(const RobustWienerModel& model, const ComplexPlane& p,
                                          const WienerFilterSpec& f) {
    WienerFilterSpec spec = f;
    if (f.kind == WienerFilterKind::kTunedNsr) {
        spec = {WienerFilterKind::kFixedNsr, evaluate_expected_psf_tuned_nsr(model, p).nominal.nsr};
    }
    return model.filter_response(p, spec, model.expected_transfer());
}

}  // namespace pinmask
