#include "optimize/metrics/spectrum_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "core/errors/error.hpp"

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

std::vector<std::uint8_t> pattern_frequencies_passed(const ComplexPlane& kernel, int n,
                                                     double passband_fraction) {
    const Eigen::Index m = kernel.rows();
    if (n < 1 || m < 1 || kernel.cols() != m || m % n != 0) {
        throw InvalidInput("kernel OTF is " + size_text(kernel) +
                           ": must be square m x m with m a multiple of the pattern size " +
                           std::to_string(n));
    }
    const double threshold = passband_fraction * kernel.abs().maxCoeff();
    std::vector<std::uint8_t> passed(static_cast<std::size_t>(n) * n, 0);
    for (Eigen::Index k = 0; k < m; ++k)
        for (Eigen::Index l = 0; l < m; ++l) {
            if (std::abs(kernel(k, l)) >= threshold) {
                passed[static_cast<std::size_t>((k % n) * n + l % n)] = 1;
            }
        }
    return passed;
}

std::string SpectralZero::message() const {
    if (!found) return "";
    std::ostringstream s;
    s << "spectral zero at pattern frequency (k, l) = (" << row << ", " << col
      << "): |P^| = " << abs_value << " < " << threshold_abs
      << " (threshold x sqrt(K)), where the kernel passes light";
    if (count > 1) s << "; " << count << " such frequencies";
    return s.str();
}

SpectralZero find_spectral_zero(const ComplexPlane& p, const std::vector<std::uint8_t>& passed,
                                double threshold) {
    check_pattern_spectrum(p);
    const int n = static_cast<int>(p.rows());
    if (passed.size() != static_cast<std::size_t>(n) * n) {
        throw InvalidInput("find_spectral_zero: passband table of " +
                           std::to_string(passed.size()) + " entries for a " + std::to_string(n) +
                           " x " + std::to_string(n) + " pattern spectrum");
    }
    if (!(threshold > 0.0) || !std::isfinite(threshold)) {
        throw invalid_field("spectral_zero_threshold", std::to_string(threshold),
                            "must be finite and > 0");
    }
    SpectralZero z;
    z.threshold_abs = threshold * std::sqrt(std::max(p(0, 0).real(), 0.0));
    z.abs_value = std::numeric_limits<double>::infinity();
    for (int k = 0; k < n; ++k)
        for (int l = 0; l < n; ++l) {
            if ((k == 0 && l == 0) || !passed[static_cast<std::size_t>(k * n + l)]) continue;
            const double a = std::abs(p(k, l));
            if (!(a < z.threshold_abs)) continue;
            ++z.count;
            if (a < z.abs_value) {
                z.abs_value = a;
                z.row = k;
                z.col = l;
            }
        }
    z.found = z.count > 0;
    if (!z.found) z.abs_value = 0.0;
    return z;
}

}  // namespace pinmask
