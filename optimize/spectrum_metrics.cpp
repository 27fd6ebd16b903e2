#include "optimize/spectrum_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace pinmask {
namespace {

std::string size_text(const ComplexPlane& p) {
    return std::to_string(p.rows()) + " x " + std::to_string(p.cols());
}

void check_pattern_spectrum(const ComplexPlane& p) {
    if (p.rows() < 1 || p.cols() != p.rows()) {
        throw InvalidInput("pattern spectrum is " + size_text(p) +
                           ": must be square n x n, n >= 1");
    }
    if (!(p(0, 0).real() >= 0.5)) {
        throw InvalidInput("pattern spectrum: P^(0) = " + std::to_string(p(0, 0).real()) +
                           ": must be the pinhole count K >= 1");
    }
}

}  // namespace

PatternSpectrumMetrics pattern_spectrum_metrics(const ComplexPlane& p) {
    check_pattern_spectrum(p);
    const Eigen::Index n = p.rows();
    PatternSpectrumMetrics m;
    m.light_gain = std::round(p(0, 0).real());
    m.open_fraction = m.light_gain / static_cast<double>(n * n);
    if (n == 1) return m;
    double min_power = std::numeric_limits<double>::infinity(), sum = 0.0, sum_log = 0.0;
    for (Eigen::Index i = 1; i < n * n; ++i) {
        const double power = std::norm(p.data()[i]);
        min_power = std::min(min_power, power);
        sum += power;
        sum_log += std::log(power);  // -inf for an exact zero: flatness 0 below
    }
    const double count = static_cast<double>(n * n - 1);
    const double zero_power = std::pow(kSpectralZeroTol * m.light_gain, 2);
    if (min_power <= zero_power) return m;  // a spectral zero: min 0, flatness 0
    m.min_abs_pattern_spectrum = std::sqrt(min_power);
    m.spectral_flatness =
        (min_power > 0.0 && sum > 0.0) ? std::exp(sum_log / count) / (sum / count) : 0.0;
    return m;
}

OtfCondition otf_condition(const ComplexPlane& p, const ComplexPlane& kernel,
                           double passband_fraction) {
    check_pattern_spectrum(p);
    const Eigen::Index n = p.rows(), m = kernel.rows();
    if (m < 1 || kernel.cols() != m || m % n != 0) {
        throw InvalidInput("kernel OTF is " + size_text(kernel) +
                           ": must be square m x m with m a multiple of the pattern size " +
                           std::to_string(n));
    }
    if (!(passband_fraction > 0.0 && passband_fraction <= 1.0)) {
        throw invalid_field("passband_fraction", std::to_string(passband_fraction),
                            "must be in (0, 1]");
    }
    const double kernel_max = kernel.abs().maxCoeff();
    if (!(kernel_max > 0.0) || !std::isfinite(kernel_max)) {
        throw InvalidInput("kernel OTF: max |K^| = " + std::to_string(kernel_max) +
                           ": must be finite and > 0");
    }
    const double threshold = passband_fraction * kernel_max;
    OtfCondition c;
    c.min_abs_otf = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < m; ++k)
        for (Eigen::Index l = 0; l < m; ++l) {
            const double kabs = std::abs(kernel(k, l));
            if (!(kabs >= threshold)) continue;
            const double a = std::abs(p(k % n, l % n)) * kabs;
            c.min_abs_otf = std::min(c.min_abs_otf, a);
            c.max_abs_otf = std::max(c.max_abs_otf, a);
            ++c.passband_frequencies;
        }
    if (c.min_abs_otf <= kSpectralZeroTol * c.max_abs_otf) c.min_abs_otf = 0.0;
    c.condition_number = c.min_abs_otf > 0.0 ? c.max_abs_otf / c.min_abs_otf
                                             : std::numeric_limits<double>::infinity();
    return c;
}

}  // namespace pinmask
