#include "decode/period.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/fft.hpp"
#include "core/resource_limits.hpp"

namespace pinmask {
namespace {

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

AxisPeriodCheck check_axis(const Plane& capture, Axis axis, int size, int expected,
                           const PeriodCheckOptions& o) {
    AxisPeriodCheck a;
    a.size_px = size;
    a.expected_px = expected;
    const char* name = axis == Axis::kRows ? "rows" : "columns";
    if (size < 2 * expected) {
        a.skip_reason = "the capture holds " + fixed(double(size) / expected, 2) +
                        " periods along the " + name + " (" + std::to_string(size) + " / " +
                        std::to_string(expected) + " px); a repeat needs at least 2";
        return a;
    }
    a.checked = true;
    const std::vector<double> profile = autocorrelation_profile(capture, axis);
    const int max_lag = std::min(size - 2, static_cast<int>(std::floor(size * o.max_lag_fraction)));
    if (const auto peak = strongest_repeat(profile, max_lag, o.min_rise)) {
        a.found = true;
        a.measured_px = peak->lag;
        a.peak_value = peak->value;
        a.peak_rise = peak->rise;
        a.matches = std::fabs(peak->lag - expected) <= o.tolerance_px;
    }
    return a;
}

}  // namespace

std::vector<double> autocorrelation_profile(const Plane& x, Axis axis) {
    if (x.size() == 0) throw InvalidInput("autocorrelation: the plane is empty");
    if (!is_all_finite(x)) throw InvalidInput("autocorrelation: the plane holds NaN or Inf");
    const int rows = static_cast<int>(x.rows()), cols = static_cast<int>(x.cols());
    const bool along_rows = axis == Axis::kRows;
    // Zero-pad along the lag axis only: at zero lag across the other axis no pair wraps around.
    const int pr = along_rows ? 2 * rows : rows, pc = along_rows ? cols : 2 * cols;
    check_memory(double(pr) * pc * 8.0 * 3.0, "the autocorrelation of the capture");
    Plane padded = Plane::Zero(pr, pc);
    padded.topLeftCorner(rows, cols) = x - x.mean();
    const Fft2 fft(pr, pc);
    ComplexPlane spectrum = fft.forward(padded);
    spectrum = spectrum.abs2().cast<std::complex<double>>();
    const Plane acf = fft.inverse(spectrum);

    const int size = along_rows ? rows : cols;
    const double other = along_rows ? cols : rows;
    std::vector<double> profile(static_cast<std::size_t>(size), 0.0);
    const double mean_square = acf(0, 0) / (double(size) * other);
    profile[0] = 1.0;
    if (!(mean_square > 0.0)) return profile;  // constant plane: nothing repeats
    for (int d = 1; d < size; ++d) {
        const double a = along_rows ? acf(d, 0) : acf(0, d);
        profile[static_cast<std::size_t>(d)] = a / ((size - d) * other) / mean_square;
    }
    return profile;
}

std::optional<ProfilePeak> strongest_repeat(const std::vector<double>& p, int max_lag,
                                            double min_rise) {
    const int n = static_cast<int>(p.size());
    max_lag = std::min(max_lag, n - 2);
    std::vector<ProfilePeak> peaks;
    double left_min = n > 1 ? p[1] : 0.0;
    for (int d = 2; d <= max_lag; ++d) {
        left_min = std::min(left_min, p[static_cast<std::size_t>(d - 1)]);
        const double prev = p[static_cast<std::size_t>(d - 1)],
                     here = p[static_cast<std::size_t>(d)],
                     next = p[static_cast<std::size_t>(d + 1)];
        if (here >= prev && here > next) peaks.push_back({double(d), here, here - left_min});
    }
    double best_rise = 0.0;
    for (const auto& pk : peaks) best_rise = std::max(best_rise, pk.rise);
    if (peaks.empty() || best_rise < min_rise) return std::nullopt;
    for (auto pk : peaks) {
        if (pk.rise < kSubharmonicFraction * best_rise) continue;
        const auto d = static_cast<std::size_t>(pk.lag);
        const double ym = p[d - 1], y0 = p[d], yp = p[d + 1];
        const double curvature = ym - 2.0 * y0 + yp;
        if (curvature < 0.0) {
            const double delta = std::clamp(0.5 * (ym - yp) / curvature, -0.5, 0.5);
            pk.lag += delta;
            pk.value = y0 - 0.25 * (ym - yp) * delta;
        }
        return pk;
    }
    return std::nullopt;  // unreachable: the best peak passes its own threshold
}

PeriodCheck check_period(const Plane& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& o) {
    if (expected_rows < 1 || expected_cols < 1) {
        throw InvalidInput("period check: expected period " + std::to_string(expected_cols) +
                           " x " + std::to_string(expected_rows) + ": both sides must be >= 1");
    }
    if (!(o.tolerance_px >= 0.0) || !(o.min_rise > 0.0) || !(o.max_lag_fraction > 0.0) ||
        !(o.max_lag_fraction <= 1.0)) {
        throw InvalidInput(
            "period check options: need tolerance_px >= 0, min_rise > 0, 0 < max_lag_fraction "
            "<= 1");
    }
    if (capture.size() == 0) throw InvalidInput("period check: the capture is empty");
    PeriodCheck check;
    check.tolerance_px = o.tolerance_px;
    check.rows =
        check_axis(capture, Axis::kRows, static_cast<int>(capture.rows()), expected_rows, o);
    check.cols =
        check_axis(capture, Axis::kCols, static_cast<int>(capture.cols()), expected_cols, o);
    return check;
}

}  // namespace pinmask
