// Torus autocorrelation of a 0/1 pattern and its sidelobe metrics.
//   R(d) = #{(i, j) : p_j - p_i = d (mod n)},  d = (dr, dc) in [0, n)^2,
// stored row-major as an n x n vector (index dr * n + dc), the layout of
// optimize/search/pattern_state.hpp. R(0) = K (the peak); every d != 0 is a sidelobe; sum_d R(d) =
// K^2. From the spectrum: R = inverse DFT of |P^|^2, rounded to integers (exact for 0/1 patterns:
// the round-off is far below 1/2 while n^2 K^2 << 2^52).
#pragma once

#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

// R from the full n x n pattern spectrum P^ (core/fft/fft.hpp convention). Throws InvalidInput for
// a non-square or empty spectrum.
std::vector<int> autocorrelation_from_spectrum(const ComplexPlane& pattern_spectrum);

struct SidelobeMetrics {
    int peak = 0;                            // R(0) = K
    int max_sidelobe = 0;                    // max over d != 0 (0 when n = 1)
    double mean_sidelobe = 0.0;              // mean over the n^2 - 1 shifts d != 0 = K(K-1)/(n^2-1)
    double integrated_sidelobe_level = 0.0;  // sum_{d != 0} R(d)^2 / R(0)^2 (linear ratio)
    double peak_to_sidelobe_ratio = 0.0;     // peak / max_sidelobe; +inf when max_sidelobe = 0
};

// Metrics of an n x n autocorrelation (size n * n, R(0) >= 1; InvalidInput otherwise). O(n^2).
SidelobeMetrics sidelobe_metrics(const std::vector<int>& autocorrelation, int n);

// sidelobe_metrics(autocorrelation_from_spectrum(P^), n).
SidelobeMetrics sidelobe_metrics_from_spectrum(const ComplexPlane& pattern_spectrum);

}  // namespace pinmask
