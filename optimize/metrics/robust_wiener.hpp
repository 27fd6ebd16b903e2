// The expected Wiener error of a mask under fabrication errors, in closed form ("robust" score,
// `--robust`, `search --objective robust`).
//
// What "expected score under errors" means: the camera's true PSF is a fabricated copy of the
// mask (errors as optimize/metrics/robust_errors.hpp: a +-b side bias, independent Gaussian
// position jitter, independently missing pinholes), while the decoder uses the nominal (design)
// PSF, as when a mask is used uncalibrated. The robust MSE is the expectation of the analytic
// Wiener MSE (optimize/metrics/analytic_error, same prior S, same noise variance sigma^2 as the
// nominal capture, same filter G built from the nominal transfer function H) over the fabrication
// errors; the robust PSNR is 10 log10(1 / robust MSE).
//
// Derivation (notation of optimize/metrics/analytic_error.hpp, N = m^2). The fabricated transfer
// function T(k) replaces H in the capture; the error (G T - 1) X^ + G E^ gives per frequency
//     E|G T - 1|^2 S + |G|^2 N sigma^2 = |G E[T] - 1|^2 S + |G|^2 (Var T S + N sigma^2).
// With kappa = K^/K^(0) the nominal kernel, kappa_s that of side d + s b (s = +-1, both signs
// averaged), J = a(k_r) a(k_c) and B = p(k_r) p(k_c) the jitter's mean and power per axis
// (robust_errors jitter_transfer), q the missing probability and pp = |P^(k mod n)|^2 / K^2:
//     E[T] = P^ kappa_s J / K      (a missing pinhole is compensated by 1/(1-q) on average)
//     Var T = |kappa_s|^2 (B / (1 - q) - |J|^2) / K     (independent pinholes)
// and for G = conj(H) w (w = 1 / (h + nsr) fixed-NSR, w = S / (h S + N sigma^2) optimal):
//     term(k) = |w pp conj(kappa) kappa_s J - 1|^2 S + w^2 pp |kappa|^2 (Var_s S + N sigma^2)
// with Var_s = |kappa_s|^2 (B / (1 - q) - |J|^2) / K. Everything depends on the pattern through
// |P^|^2 and K only. Without errors (kappa_s = kappa, J = B = 1, q = 0) this is the nominal
// term; evaluate() then returns the nominal figure itself, so zero errors give exactly the
// nominal score. Cost per evaluation: O(m^2) per bias sign, plus the nominal evaluation.
//
// Not modelled: the changed light of a fabricated mask (brightness is the user's exposure; the
// noise variance is the nominal capture's), and errors of the film's transmission or leak.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "design/pattern/mask.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/robust_errors.hpp"

namespace pinmask {

struct RobustError {
    AnalyticError nominal;  // the analytic error of the design (its filter, noise variance)
    double mse = 0.0;       // expected MSE over the fabrication errors, same filter
    double psnr_db = 0.0;   // 10 log10(1 / mse)
    double loss_db() const { return nominal.psnr_db - psnr_db; }
};

// The robust filter (RobustWienerModel::evaluate_robust_filter) as the inputs of an ordinary
// Wiener decode (`score --robust-decoder`, `decode --psf robust-psf --nsr-map robust-nsr`):
//     G = conj(E T) S / (E|T|^2 S + N sigma^2) = conj(E T) / (|E T|^2 + NSR),
//     NSR = (E|T|^2 - |E T|^2) + N sigma^2 / S,
// i.e. the Wiener filter of the EXPECTED fabricated PSF (transfer E T) with a per-frequency NSR:
// the fabrication variance plus the noise-to-signal ratio.
//   psf  the expected fabricated PSF, m x m in design/psf/psf's frame (as mask_psf: DFT(psf) = E
//   T),
//        sum 1, real part of the inverse DFT of E T (E T is Hermitian: the mean of real PSFs);
//        values within rounding of 0 may be -1e-17.
//   nsr  the NSR per frequency, m x m, indexed like fft2 output (row k, column l is frequency
//        (k / m, l / m)), as decode's WienerParams::nsr_per_frequency. Where the prior has no
//        power (S = 0, the robust filter is 0) the NSR is kRobustNsrNoSignal.
// decode's deconvwnr floor (max(|H|^2 + NSR, 1.49e-8)) is the only difference from G: it acts
// where E|T|^2 + N sigma^2 / S < 1.49e-8 (`floored` counts those frequencies).
inline constexpr double kRobustNsrNoSignal = 1e30;
struct RobustDecoderInputs {
    Plane psf;
    Plane nsr;
    int floored = 0;
};

class RobustWienerModel {
  public:
    // The template's camera, PSF settings and n (pinholes ignored); errors validated against it
    // (InvalidInput naming --robust and the key). The prior is at the period m = n ppc.
    RobustWienerModel(const Mask& tmpl, FabricationErrors errors, ScenePrior prior,
                      NoiseModel noise);

    const FabricationErrors& errors() const { return errors_; }
    const AnalyticWienerModel& nominal() const { return *nominal_; }
    int cases() const { return static_cast<int>(cross_.size()); }

    // The filter is the nominal decoder's (fixed NSR or per-frequency optimal), built from the
    // nominal PSF (an uncalibrated camera).
    RobustError evaluate(const ComplexPlane& pattern_spectrum, const WienerFilterSpec& f) const;
    // The fixed-NSR filter with the NSR tuned for the nominal mask (what a user tuning the
    // design would pick), then its robust error.
    RobustError evaluate_tuned_nsr(const ComplexPlane& pattern_spectrum) const;

    // The decoder chosen for the errors (the decoder is part of the design):
    // per frequency the linear filter minimising the EXPECTED fabricated error,
    //     G = conj(E T) S / (E|T|^2 S + N sigma^2),  E T = P^ D / K,
    //     E|T|^2 = pp E_s|kappa_s J|^2 + E_s Var_s / K,
    // whose expected fabricated term is S (E|T|^2 S - |E T|^2 S + N sigma^2) / (E|T|^2 S +
    // N sigma^2). No fixed or tuned NSR, no per-frequency filter and no decoder PSF does better
    // on the fabricated masks (it is the minimum of a quadratic per frequency). `nominal.mse` /
    // `nominal.psnr_db` are the NOMINAL capture decoded with this same G (nominal.nsr = 0).
    RobustError evaluate_robust_filter(const ComplexPlane& pattern_spectrum) const;

    // A lower bound on the expected fabricated MSE of ANY pattern decoded by ANY linear
    // shift-invariant filter at any noise level: per frequency min_u E|u T - 1|^2 S =
    // S (1 - |E T|^2 / E|T|^2) >= S (1 - |E_s kappa_s|^2 / E_s |kappa_s|^2) (the pattern and the
    // jitter mean cancel; jitter and missing variance, noise and spectral zeros only add). It
    // is the size bias's share: 0 without a bias. Per pixel, same units as RobustError::mse.
    double pattern_independent_floor_mse() const;

    // Frequency responses G (m x m, applied as X~ = G C^ to the capture's unnormalised DFT, in
    // design/psf/psf's frame: H = P^(k mod n) kappa / K is the DFT of the sum-1 mask PSF), for the
    // simulation to decode with (tests/research/fabricated_sample fabricated_filter_quality):
    // the robust filter above, and the filters of evaluate / evaluate_tuned_nsr, G = conj(H_D) w
    // with H_D = P^ D / K for the decoder's kernel OTF D (kappa unless given),
    // w = 1 / (|H_D|^2 + nsr) (fixed or tuned NSR) or S / (|H_D|^2 S + N sigma^2) (optimal). The
    // noise variance is the nominal capture's, as in the figures.
    ComplexPlane robust_filter_response(const ComplexPlane& pattern_spectrum) const;
    // The robust filter as a Wiener decoder's PSF and per-frequency NSR (RobustDecoderInputs).
    RobustDecoderInputs robust_decoder_inputs(const ComplexPlane& pattern_spectrum) const;
    ComplexPlane filter_response(const ComplexPlane& pattern_spectrum,
                                 const WienerFilterSpec& f) const;
    // A decoder built from another kernel OTF D (m x m, e.g. expected_transfer()); f is a fixed
    // NSR or the optimal filter (a tuned NSR depends on D: tune it with mismatch_mse).
    ComplexPlane filter_response(const ComplexPlane& pattern_spectrum, const WienerFilterSpec& f,
                                 const ComplexPlane& decoder_otf) const;

    // The parts of the closed form, for decoders built from another PSF than the design's
    // (tests/research/expected_psf_decoder), all m x m: the nominal kernel OTF kappa = K^/K^(0);
    // per bias sign (one case without a bias, two with) the fabricated transfer kappa_s J and
    // the variance |kappa_s|^2 (B / (1 - q) - |J|^2) (without errors: kappa and 0); their mean
    // over the signs D = E_s kappa_s J (the kernel part of the expected fabricated PSF).
    const ComplexPlane& kernel_otf() const { return kappa_; }
    const std::vector<ComplexPlane>& fabricated_transfers() const { return transfers_; }
    const std::vector<Plane>& fabricated_variances() const { return variance_; }
    const ComplexPlane& expected_transfer() const { return expected_; }
    // (1/N^2) sum over the truth cases (averaged) of the expected error of the filter built from
    // the decoder's |D|^2 (`decoder_power`) and spec f (fixed NSR or optimal) against true
    // transfer functions with conj(D) x mean `cross[c]` and variance `variance[c]` / K (empty:
    // none), for the pattern spectrum p and the nominal capture's noise variance `sigma2`.
    double mismatch_mse(const ComplexPlane& p, double sigma2, const WienerFilterSpec& f,
                        const Plane& decoder_power, const std::vector<ComplexPlane>& cross,
                        const std::vector<Plane>& variance) const;

  private:
    // The per-frequency quantities of the robust filter for a pattern spectrum, on the m x m
    // grid: E T = P^ D / K (the expected fabricated transfer), E|T|^2, and N sigma^2 of the
    // nominal capture. robust_filter_response and robust_decoder_inputs are built from them.
    struct RobustTerms {
        ComplexPlane mean;  // E T
        Plane power;        // E|T|^2
        double n_sigma2 = 0.0;
    };
    RobustTerms robust_terms(const ComplexPlane& p) const;

    FabricationErrors errors_;
    std::shared_ptr<AnalyticWienerModel> nominal_;
    int n_ = 0;
    std::vector<ComplexPlane> cross_;  // per bias sign: conj(kappa) kappa_s J (empty: no errors)
    std::vector<ComplexPlane> transfers_;  // per bias sign: kappa_s J (no errors: kappa)
    std::vector<Plane> variance_;  // per bias sign: |kappa_s|^2 (B / (1 - q) - |J|^2) (or 0)
    // The robust filter's: D = E_s kappa_s J, |D|^2, conj(D) kappa (the nominal capture),
    // E_s |kappa_s J|^2 and E_s Var_s.
    ComplexPlane kappa_;  // the nominal kernel OTF K^ / K^(0)
    ComplexPlane expected_;
    Plane expected_power_;
    ComplexPlane expected_nominal_cross_;
    Plane fabricated_power_, mean_variance_;
    double floor_mse_ = 0.0;
};

}  // namespace pinmask
