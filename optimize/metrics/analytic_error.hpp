// Expected mean squared error of Wiener decoding, in closed form, over one period of N pixels.
//
// Convention (core/fft/fft.hpp, unnormalised forward DFT). The capture is c = a (*) x + e with a
// the mask PSF normalised to sum 1 (the light level lives in the noise model,
// optimize/simulate/noise_model), e white noise of per-pixel variance sigma^2. In the DFT: C^ = H
// X^ + E^ with H = A^ / A^(0), H(0) = 1, and E|E^(k)|^2 = N sigma^2 at every k. A linear filter X~
// = G C^ leaves the error X~ - X^ = (G H - 1) X^ + G E^; by Parseval the pixel-sum of squares is
// (1/N) sum_k |.|^2, so with S(k) = E|X^(k)|^2 (optimize/simulate/scene_prior) and scene and noise
// independent,
//     MSE = (1/N^2) sum_k [ |1 - G H|^2 S(k) + |G|^2 N sigma^2 ]      (per pixel).
// Fixed-NSR filter (decode's Wiener, deconvwnr parity): G = conj(H) / (|H|^2 + nsr), so with
// h = |H|^2:  MSE = (1/N^2) sum_k [ nsr^2 S(k) + h N sigma^2 ] / (h + nsr)^2.
// Optimal per-frequency Wiener filter: G = conj(H) S / (h S + N sigma^2), giving
//     MSE = (1/N^2) sum_k S(k) N sigma^2 / (h S(k) + N sigma^2)
// (a frequency with h S + N sigma^2 = 0 contributes S(k): nothing to recover, nothing lost).
// Both depend on H through h only. Expected PSNR = 10 log10(1 / MSE) for scenes in [0, 1].
//
// The noise variance comes from the noise model (optimize/simulate/noise_model.hpp): Gaussian at an
// SNR uses the expected mean(c^2) = (1/N^2) sum_k h S(k); the photon model uses the prior's mean
// scene value and K = P^(0).
//
// Mask OTF factorisation (docs/design.md section 2): h(k) = |P^(k mod n)|^2 |K^(k)|^2 / (K^2 |K^(0)|^2)
// with P^ the n x n pattern spectrum and K^ the m x m kernel spectrum, m = n * n_px.
#pragma once

#include "core/image/image.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/scene_prior.hpp"

namespace pinmask {

// kFixedNsr: decode's Wiener at a given NSR; kOptimal: the per-frequency Wiener filter (a lower
// bound no decoder here reaches); kTunedNsr: decode's Wiener with the NSR that minimises the
// expected MSE of this pattern (evaluate_tuned_nsr), which is what the simulated figures
// (optimize/metrics/simulated_metrics, NSR tuned per mask) and `search --photons` judge by.
enum class WienerFilterKind { kFixedNsr, kOptimal, kTunedNsr };

struct WienerFilterSpec {
    WienerFilterKind kind = WienerFilterKind::kFixedNsr;
    double nsr = 0.01;  // kFixedNsr: scalar noise-to-signal ratio, > 0 and finite
};

// h = |H|^2 on the m x m period for the sum-1 mask PSF (formula above). The kernel spectrum is
// m x m, m a multiple of n, K^(0) != 0; the pattern spectrum n x n with P^(0) = K >= 1.
Plane mask_otf_power(const ComplexPlane& pattern_spectrum, const ComplexPlane& kernel_otf);

// Expected mean(c^2) of the noiseless capture: (1/N^2) sum_k h S(k). Same sizes required.
double expected_mean_square_capture(const Plane& otf_power, const Plane& prior_power);

// Per-pixel MSE of the filter for |H|^2 = otf_power, prior S and white noise variance sigma^2
// (>= 0). InvalidInput for mismatched sizes, a negative variance or a bad NSR.
double wiener_mse(const Plane& otf_power, const Plane& prior_power, double noise_variance,
                  const WienerFilterSpec& filter);

struct AnalyticError {
    double mse = 0.0;                  // expected per-pixel MSE
    double psnr_db = 0.0;              // 10 log10(1 / mse)
    double noise_variance = 0.0;       // sigma^2 per pixel, normalised capture units
    double mean_square_capture = 0.0;  // expected mean(c^2)
    double nsr = 0.0;                  // the fixed NSR used (tuned or given); 0 for kOptimal
};

// The analytic error as a function of the pattern spectrum, with everything else fixed: built
// once per (kernel, prior, noise), evaluated per candidate pattern in O(m^2) without FFTs or
// allocations beyond an n x n scratch. Const member functions are thread-safe.
class AnalyticWienerModel {
  public:
    // kernel_otf: full m x m spectrum of the single-pinhole kernel (K^(0) != 0); prior: m x m.
    // The noise model is validated. InvalidInput on size mismatch.
    AnalyticWienerModel(const ComplexPlane& kernel_otf, ScenePrior prior, NoiseModel noise);

    int period() const { return static_cast<int>(kernel_power_.rows()); }
    const ScenePrior& prior() const { return prior_; }
    const NoiseModel& noise() const { return noise_; }

    // Expected error of the pattern (n x n spectrum, n divides m) under the given filter
    // (kTunedNsr: evaluate_tuned_nsr).
    AnalyticError evaluate(const ComplexPlane& pattern_spectrum,
                           const WienerFilterSpec& filter) const;

    // The fixed-NSR filter with the NSR that minimises the expected MSE (golden section on
    // log10 NSR, optimize/metrics/nsr_tuning.hpp).
    AnalyticError evaluate_tuned_nsr(const ComplexPlane& pattern_spectrum) const;

    // |K^|^2 / |K^(0)|^2 on the m x m period (optimize/metrics/aliased_wiener groups it by alias).
    const Plane& kernel_power() const { return kernel_power_; }
    // Per-pixel noise variance sigma^2 of the noise model for these capture statistics.
    double noise_variance(double mean_square_capture, int open_cells, int total_cells) const;

  private:
    Plane pattern_power(const ComplexPlane& pattern_spectrum) const;
    double mse_of(const Plane& pattern_power, double sigma2, const WienerFilterSpec& f) const;
    double mean_square_of(const Plane& pattern_power) const;

    Plane kernel_power_;  // |K^|^2 / |K^(0)|^2, m x m
    ScenePrior prior_;
    NoiseModel noise_;
};

}  // namespace pinmask
