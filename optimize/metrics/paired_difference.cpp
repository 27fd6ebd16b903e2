#include "optimize/metrics/paired_difference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

constexpr double kZ95 = 1.959963984540054;  // the normal's two-sided 95 % quantile

bool significant(double d, double se) {
    return std::isfinite(se) && std::abs(d) >= kSignificantStandardErrors * se && d != 0.0;
}

}  // namespace

PairedDifference paired_difference(const std::vector<double>& b, const std::vector<double>& a) {
    if (b.size() != a.size() || b.empty())
        throw InvalidInput("paired difference: needs the same number (>= 1) of samples of both");
    const double s = static_cast<double>(b.size());
    double mean = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) mean += b[i] - a[i];
    mean /= s;
    PairedDifference r;
    r.difference = mean;
    r.samples = static_cast<int>(b.size());
    if (b.size() < 2) {
        r.standard_error = std::numeric_limits<double>::quiet_NaN();
        return r;
    }
    double ss = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) ss += (b[i] - a[i] - mean) * (b[i] - a[i] - mean);
    r.standard_error = std::sqrt(ss / (s - 1.0)) / std::sqrt(s);
    r.significant = significant(r.difference, r.standard_error);
    return r;
}

PairedDifference exact_difference(double b, double a) {
    PairedDifference r;
    r.difference = b - a;
    r.exact = true;
    r.significant = std::isfinite(r.difference) && r.difference != 0.0;
    return r;
}

MedianEstimate median_estimate(std::vector<double> values) {
    if (values.empty()) throw InvalidInput("median: needs at least one value");
    std::sort(values.begin(), values.end());
    const long long s = static_cast<long long>(values.size());
    MedianEstimate r;
    r.median = values[static_cast<std::size_t>((s - 1) / 2)];
    if (s < 2) {
        r.standard_error = std::numeric_limits<double>::quiet_NaN();
        return r;
    }
    const double half = kZ95 * std::sqrt(static_cast<double>(s)) / 2.0;
    const long long j = std::clamp(static_cast<long long>(std::floor(s / 2.0 - half)), 1LL, s);
    const long long k = std::clamp(static_cast<long long>(std::ceil(s / 2.0 + 1.0 + half)), 1LL, s);
    r.standard_error =
        (values[static_cast<std::size_t>(k - 1)] - values[static_cast<std::size_t>(j - 1)]) /
        (2.0 * kZ95);
    return r;
}

}  // namespace pinmask
