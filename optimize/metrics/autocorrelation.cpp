#include "optimize/metrics/autocorrelation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"

namespace pinmask {

std::vector<int> autocorrelation_from_spectrum(const ComplexPlane& spectrum) {
    const Eigen::Index n = spectrum.rows();
    if (n < 1 || spectrum.cols() != n) {
        throw InvalidInput("pattern spectrum is " + std::to_string(spectrum.rows()) + " x " +
                           std::to_string(spectrum.cols()) + ": must be square n x n, n >= 1");
    }
    // |P^|^2 is real and even, so the half spectrum of the c2r transform suffices.
    const Fft2 fft(static_cast<int>(n), static_cast<int>(n));
    ComplexPlane half(n, fft.half_cols());
    for (Eigen::Index k = 0; k < n; ++k)
        for (Eigen::Index l = 0; l < fft.half_cols(); ++l) half(k, l) = std::norm(spectrum(k, l));
    const Plane r = fft.inverse(half);
    std::vector<int> out(static_cast<std::size_t>(n * n));
    for (Eigen::Index i = 0; i < n * n; ++i) out[i] = static_cast<int>(std::lround(r.data()[i]));
    return out;
}

SidelobeMetrics sidelobe_metrics(const std::vector<int>& r, int n) {
    if (n < 1 || r.size() != static_cast<std::size_t>(n) * n) {
        throw InvalidInput("autocorrelation has " + std::to_string(r.size()) +
                           " entries: must be n * n for n = " + std::to_string(n));
    }
    if (r[0] < 1) {
        throw InvalidInput("autocorrelation peak R(0) = " + std::to_string(r[0]) +
                           ": must be >= 1 (at least one pinhole)");
    }
    SidelobeMetrics m;
    m.peak = r[0];
    double sum = 0.0, sum_sq = 0.0;
    for (std::size_t i = 1; i < r.size(); ++i) {
        m.max_sidelobe = std::max(m.max_sidelobe, r[i]);
        sum += r[i];
        sum_sq += static_cast<double>(r[i]) * r[i];
    }
    const double shifts = static_cast<double>(r.size() - 1);
    m.mean_sidelobe = shifts > 0 ? sum / shifts : 0.0;
    m.integrated_sidelobe_level = sum_sq / (static_cast<double>(m.peak) * m.peak);
    m.peak_to_sidelobe_ratio = m.max_sidelobe > 0 ? static_cast<double>(m.peak) / m.max_sidelobe
                                                  : std::numeric_limits<double>::infinity();
    return m;
}

SidelobeMetrics sidelobe_metrics_from_spectrum(const ComplexPlane& spectrum) {
    return sidelobe_metrics(autocorrelation_from_spectrum(spectrum),
                            static_cast<int>(spectrum.rows()));
}

}  // namespace pinmask
