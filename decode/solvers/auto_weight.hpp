// The automatic weight of the closed-form decoders (Wiener's scalar NSR, Tikhonov's lambda):
// the weight that minimises the expected squared error of the estimate, ||x_hat - x||^2, under
// a scene spectrum fitted to the capture (an empirical-Bayes risk rule).
//
// Model, per frequency k of the working grid (H the OTF, |L|^2 the regulariser's symbol, 1 for
// Wiener and Tikhonov-identity): P = H X + E with E white of per-pixel variance sigma^2 (from
// the capture, decode/solvers/noise_estimate.hpp, unless given) and E|X(k)|^2 / N = S(k). For the
// filter G = conj(H) / (|H|^2 + w |L|^2) the expected error is
//   risk(w) = sum_k (w |L|^2 / (|H|^2 + w |L|^2))^2 S(k) + |H|^2 / (|H|^2 + w |L|^2)^2 sigma^2.
// S is a power law S(f) = c |f|^-alpha (alpha in [0, 4], |f| in cycles per pixel) fitted by
// weighted least squares in log-log to the capture's own spectrum in 12 logarithmic radial
// bands, S_band = (sum |P|^2 / N - sigma^2) / sum |H|^2, over the bands where the signal at
// least doubles the noise; the zero frequency keeps its measured S. A white scene (alpha = 0)
// gives the Wiener optimum w = sigma^2 / c, i.e. NSR = sigma_n^2 / sigma_x^2 in per-pixel
// variances (deconvwnr's units, for a PSF of unit sum). The weight is searched over
// w / max|H|^2 in [1e-10, 1e2]: a grid of 4 points per decade, then 40 golden-section steps
// in log w around the grid's best point.
// Linear model: the capture is zero-padded to the working grid (as the filter sees it), and the
// light that would fall beyond the sensor, which the filter reads as zero, is an error of the
// same kind as noise: the power per frequency is (sigma^2 n + m (N - n)) / N, n the capture's
// pixels, N the grid's, m the mean square of the capture's border band (1/16 of its smaller
// side wide), the level of the light at the sensor's edges (counting the noise alone chooses
// far too small an NSR on a frame-filling lensless capture).
// Units: the weight is dimensionless and the same for the capture times any factor (both
// S and sigma^2 scale by its square).
#pragma once

#include <optional>

#include "core/image/image.hpp"

namespace pinmask {

struct AutoWeight {
    double weight = 0.0;       // the NSR (Wiener) or lambda (Tikhonov, TV) chosen
    double noise_sigma = 0.0;  // per-pixel noise sigma used, capture units
    double alpha = 0.0;        // fitted exponent of the scene spectrum (0 for TV: not fitted)
};

// capture: the decoded window (capture_pixels = its size); otf: H on the working grid (half
// spectrum rows x (cols / 2 + 1)); symbol: |L|^2 on the same half spectrum. The capture is
// zero-padded to rows x cols at the top-left (its place in the working grid; the error depends
// only on |P|). noise_sigma: the known sigma, else estimated from the capture.
AutoWeight choose_closed_form_weight(const Plane& capture, const ComplexPlane& otf,
                                     const Plane& symbol, int rows, int cols,
                                     std::optional<double> noise_sigma = std::nullopt);

// TV-L2 (1/2 ||A x - p||^2 + lambda TV(x)): lambda = k sigma ||a||_2 g(SNR) (k: auto_weight.cpp),
// sigma the per-pixel noise (estimated from the capture unless given), ||a||_2 the PSF's l2 norm
// (the rms of |H|: the gain of the data term a typical frequency sees). Denoising with the data
// term ~ ||a||_2^2 ||x - x~||^2 / 2 and x~'s noise sigma / ||a||_2 wants a TV weight proportional
// to that noise, times ||a||_2^2: lambda ~ sigma ||a||_2. That holds at low light; at a higher
// SNR (the capture's mean over sigma) the error left is more the weight's blur than the noise,
// and the best weight falls faster than sigma: g = min(1, (SNR0 / SNR)^beta) (SNR0, beta:
// auto_weight.cpp), so lambda ~ sigma^(1 + beta) well above SNR0. The weight is in capture units
// and follows the capture's scale (SNR is scale-free); a PSF scaled by t scales it by t.
// The constants were calibrated on a training set of photographs and cameras disjoint from those
// of the table in docs/decoding.md (scripts/autoreg_table.py --calibrate-tv says which).
AutoWeight choose_tv_weight(const Plane& capture, const Plane& psf,
                            std::optional<double> noise_sigma = std::nullopt);

// risk(w) above for a known S (half spectrum) and per-frequency noise power sigma^2 (the
// rule's objective, exposed for tests).
double closed_form_risk(const ComplexPlane& otf, const Plane& symbol, const Plane& scene_power,
                        double noise_power, int cols, double weight);

}  // namespace pinmask
