// Spectral metrics of a pattern and of the mask OTF (docs/design.md section 2).
//   P^  the full n x n DFT of the 0/1 pattern (core/fft/fft.hpp convention), P^(0) = K
//   K^  the full m x m DFT of the single-pinhole kernel on the period grid, m = n * n_px
//   A^(k) = P^(k mod n) K^(k)   the OTF of the mask PSF on the m x m period (k per axis)
// Frequencies k != 0 exclude only the DC term (0, 0).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

// |P^(k)| <= kSpectralZeroTol * K, and |A^(k)| <= kSpectralZeroTol * max |A^|, count as exact
// zeros: FFT or incremental-update round-off leaves ~1e-15 K where the exact value is 0, and
// such a value must not turn a zero into a finite (but meaningless) flatness or condition.
inline constexpr double kSpectralZeroTol = 1e-9;

struct PatternSpectrumMetrics {
    double min_abs_pattern_spectrum = 0.0;  // min |P^(k)| over k != 0 (0 when n = 1: none)
    // Geometric over arithmetic mean of |P^(k)|^2 over k != 0: 1 for a flat spectrum (a single
    // pinhole), 0 when some |P^(k)| vanishes (also 0 when n = 1).
    double spectral_flatness = 0.0;
    double open_fraction = 0.0;  // K / n^2
    double light_gain = 0.0;     // K: light through the mask relative to one pinhole
};

// Metrics of the full n x n pattern spectrum (square, n >= 1, Re P^(0) >= 0.5, i.e. K >= 1;
// InvalidInput otherwise). O(n^2), no FFT.
PatternSpectrumMetrics pattern_spectrum_metrics(const ComplexPlane& pattern_spectrum);

// The kernel's passband: frequencies where |K^(k)| >= kPassbandFraction * max |K^|. 0.1 keeps
// what the kernel passes above -20 dB of its peak; beyond that the kernel, not the pattern,
// decides whether a frequency can be recovered.
inline constexpr double kPassbandFraction = 0.1;

struct OtfCondition {
    double condition_number = 0.0;  // max |A^| / min |A^| over the passband (+inf if min is 0)
    double min_abs_otf = 0.0;       // min |A^| over the passband
    double max_abs_otf = 0.0;       // max |A^| over the passband
    long long passband_frequencies = 0;
};

// Condition of A^(k) = P^(k mod n) K^(k) over the kernel's passband. The kernel spectrum is
// m x m with m a multiple of n (InvalidInput otherwise); passband_fraction in (0, 1]. O(m^2).
OtfCondition otf_condition(const ComplexPlane& pattern_spectrum, const ComplexPlane& kernel_otf,
                           double passband_fraction = kPassbandFraction);

// ---- Spectral zeros ----
// A pattern frequency k != 0 (n x n) is a spectral zero when |P^(k)| < threshold * sqrt(K)
// (sqrt(K) is the flat-spectrum level with the pattern's energy) while the kernel still passes
// light at one of its aliases k + n j on the m x m period (|K^| >= kPassbandFraction max |K^|).
// There the mask OTF A^ = P^ K^ loses the scene: no decoder brings it back. The default
// threshold 1e-3 is -60 dB of the flat level, far below any noise floor a capture reaches.
inline constexpr double kSpectralZeroThreshold = 1e-3;

// Per pattern frequency (n x n, row-major): 1 when some alias k + n j is in the kernel's
// passband. The kernel OTF is m x m with m a multiple of n (InvalidInput otherwise).
std::vector<std::uint8_t> pattern_frequencies_passed(const ComplexPlane& kernel_otf, int n,
                                                     double passband_fraction = kPassbandFraction);

struct SpectralZero {
    bool found = false;
    int count = 0;               // spectral zeros among the passed frequencies
    int row = 0, col = 0;        // the deepest one (frequency indices in 0 .. n-1)
    double abs_value = 0.0;      // its |P^|
    double threshold_abs = 0.0;  // threshold * sqrt(K)
    // "spectral zero at pattern frequency (k, l) = (0, 4): |P^| = 0 < 0.0045 (1e-3 sqrt(K)),
    // where the kernel passes light; 3 such frequencies", or "" when none.
    std::string message() const;
};

// O(n^2). `passed` from pattern_frequencies_passed (size n * n), threshold > 0.
SpectralZero find_spectral_zero(const ComplexPlane& pattern_spectrum,
                                const std::vector<std::uint8_t>& passed,
                                double threshold = kSpectralZeroThreshold);

}  // namespace pinmask
