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

// The smallest power of two >= n: the transform sizes FFTW does fastest (measured on the
// bench capture: 4096 points cost about half of 3456 or 5000).
int fft_size(int n) {
    int m = 1;
    while (m < n) m *= 2;
    return m;
}

// The samples the check reads along the lag axis (`axis`) of a rows x cols frame whose value at
// (r, c) is at(r, c): every line across when there are at most kAcrossStrips * kStripWidth of
// them, else kAcrossStrips strips of kStripWidth adjacent lines spread evenly across the frame,
// each strip averaged into one line. A capture periodic along the lag axis gives strips exactly
// periodic with the same period; reading a few strips instead of the frame keeps the check's
// cost a small fraction of a one-period decode's.
template <class At>
Plane strips_across(Eigen::Index rows, Eigen::Index cols, Axis axis, const At& at) {
    const Eigen::Index size = axis == Axis::kRows ? rows : cols;
    const Eigen::Index across = axis == Axis::kRows ? cols : rows;
    const bool all = across <= Eigen::Index{kAcrossStrips} * kStripWidth;
    const Eigen::Index n = all ? across : kAcrossStrips;
    const Eigen::Index w = all ? 1 : kStripWidth;
    Plane out = Plane::Zero(axis == Axis::kRows ? size : n, axis == Axis::kRows ? n : size);
    for (Eigen::Index k = 0; k < n; ++k) {
        // Strip k is centred on (k + 1/2) across / n.
        const Eigen::Index first =
            all ? k
                : std::clamp<Eigen::Index>((2 * k + 1) * across / (2 * n) - w / 2, 0, across - w);
        for (Eigen::Index j = first; j < first + w; ++j) {
            if (axis == Axis::kRows) {
                for (Eigen::Index i = 0; i < size; ++i) out(i, k) += at(i, j);
            } else {
                for (Eigen::Index i = 0; i < size; ++i) out(k, i) += at(j, i);
            }
        }
    }
    if (w > 1) out /= static_cast<double>(w);
    return out;
}

// The parabola through the three samples around integer lag d (sub-pixel refinement).
ProfilePeak refine(const std::vector<double>& p, int d, double rise) {
    ProfilePeak pk{double(d), p[static_cast<std::size_t>(d)], rise};
    const double ym = p[static_cast<std::size_t>(d - 1)], y0 = p[static_cast<std::size_t>(d)],
                 yp = p[static_cast<std::size_t>(d + 1)];
    const double curvature = ym - 2.0 * y0 + yp;
    if (curvature < 0.0) {
        const double delta = std::clamp(0.5 * (ym - yp) / curvature, -0.5, 0.5);
        pk.lag += delta;
        pk.value = y0 - 0.25 * (ym - yp) * delta;
    }
    return pk;
}

// The repeat nearest the expected lag: the highest local maximum of the profile within
// +-window of it (rise measured as in strongest_repeat), if any.
std::optional<ProfilePeak> repeat_near(const std::vector<double>& p, int expected, int window,
                                       int max_lag) {
    const int lo = std::max(2, expected - window), hi = std::min(max_lag, expected + window);
    if (lo > hi || hi + 1 >= static_cast<int>(p.size())) return std::nullopt;
    double left_min = p[1];
    for (int d = 2; d < lo; ++d) left_min = std::min(left_min, p[static_cast<std::size_t>(d)]);
    std::optional<ProfilePeak> best;
    for (int d = lo; d <= hi; ++d) {
        left_min = std::min(left_min, p[static_cast<std::size_t>(d - 1)]);
        const double here = p[static_cast<std::size_t>(d)];
        if (here >= p[static_cast<std::size_t>(d - 1)] &&
            here > p[static_cast<std::size_t>(d + 1)] && (!best || here > best->value)) {
            best = ProfilePeak{double(d), here, here - left_min};
        }
    }
    if (best) return refine(p, static_cast<int>(best->lag), best->rise);
    return best;
}

AxisPeriodCheck check_axis(const Plane& strips, Axis axis, int size, int expected,
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
    a.tolerance_px = std::max(o.tolerance_px, o.relative_tolerance * expected);
    const int max_lag = std::min(size - 2, static_cast<int>(std::floor(size * o.max_lag_fraction)));
    // Lags up to max_lag + 1: the searches compare each lag with its right neighbour.
    const std::vector<double> profile = autocorrelation_profile(strips, axis, max_lag + 1);
    const auto best = strongest_repeat(profile, max_lag, o.min_rise);
    // A capture that repeats at P also repeats at every multiple, and a pattern may nearly repeat
    // at a fraction of P: what the decoder needs is a repeat at P itself, so the peak near the
    // expected lag is taken when it is as strong as a repeat (same rule as the subharmonics).
    const int window = std::max(2, static_cast<int>(std::ceil(o.search_fraction * expected)));
    auto near = repeat_near(profile, expected, window, max_lag);
    if (near &&
        (near->rise < o.min_rise || (best && near->rise < kSubharmonicFraction * best->rise))) {
        near.reset();
    }
    const std::optional<ProfilePeak> chosen = near ? near : best;
    if (!chosen) {
        // Nothing repeats measurably (one lit period, as an exact-geometry capture of a 2 x 2
        // mask gives, or a dark or flat scene): the pitch cannot be checked, which is not a
        // contradiction of the PSF. Said as a skip, with the reason.
        a.checked = false;
        a.skip_reason = std::string("no repeat found along the ") + name + " (expected every " +
                        std::to_string(expected) +
                        " px): the capture holds no measurable repeat (a single lit period, a "
                        "dark or flat scene), so its pitch cannot be checked";
        return a;
    }
    {
        a.found = true;
        a.measured_px = chosen->lag;
        a.peak_value = chosen->value;
        a.peak_rise = chosen->rise;
        a.matches = std::fabs(chosen->lag - expected) <= a.tolerance_px;
    }
    return a;
}

}  // namespace

std::vector<double> autocorrelation_profile(const Plane& x, Axis axis, int max_lag) {
    if (x.size() == 0) throw InvalidInput("autocorrelation: the plane is empty");
    if (!is_all_finite(x)) throw InvalidInput("autocorrelation: the plane holds NaN or Inf");
    const int rows = static_cast<int>(x.rows()), cols = static_cast<int>(x.cols());
    const bool along_rows = axis == Axis::kRows;
    const int side = along_rows ? rows : cols;
    const int last = max_lag < 0 ? side - 1 : std::min(max_lag, side - 1);
    // Zero-pad along the lag axis only (at zero lag across the other axis no pair wraps around),
    // to side + last samples: no lag up to `last` wraps around.
    const int pr = along_rows ? fft_size(rows + last) : rows;
    const int pc = along_rows ? cols : fft_size(cols + last);
    check_memory(double(pr) * pc * 8.0 * 3.0, "the autocorrelation of the capture");
    Plane padded = Plane::Zero(pr, pc);
    padded.topLeftCorner(rows, cols) = x - x.mean();
    const Fft2 fft(pr, pc);
    ComplexPlane spectrum = fft.forward(padded);
    spectrum = spectrum.abs2().cast<std::complex<double>>();
    const Plane acf = fft.inverse(spectrum);

    const int size = along_rows ? rows : cols;
    const double other = along_rows ? cols : rows;
    std::vector<double> profile(static_cast<std::size_t>(last + 1), 0.0);
    const double mean_square = acf(0, 0) / (double(size) * other);
    profile[0] = 1.0;
    if (!(mean_square > 0.0)) return profile;  // constant plane: nothing repeats
    for (int d = 1; d <= last; ++d) {
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
    for (const auto& pk : peaks) {
        if (pk.rise < kSubharmonicFraction * best_rise) continue;
        return refine(p, static_cast<int>(pk.lag), pk.rise);
    }
    return std::nullopt;  // unreachable: the best peak passes its own threshold
}

namespace {

// The check on the strips of a rows x cols frame read through at(r, c).
template <class At>
PeriodCheck check_frame(Eigen::Index rows, Eigen::Index cols, const At& at, int expected_rows,
                        int expected_cols, const PeriodCheckOptions& o) {
    if (expected_rows < 1 || expected_cols < 1) {
        throw InvalidInput("period check: expected period " + std::to_string(expected_cols) +
                           " x " + std::to_string(expected_rows) + ": both sides must be >= 1");
    }
    if (!(o.tolerance_px >= 0.0) || !(o.relative_tolerance >= 0.0) || !(o.min_rise > 0.0) ||
        !(o.max_lag_fraction > 0.0) || !(o.max_lag_fraction <= 1.0) ||
        !(o.search_fraction >= 0.0) || !(o.search_fraction <= 1.0)) {
        throw InvalidInput(
            "period check options: need tolerance_px >= 0, relative_tolerance >= 0, min_rise > 0, "
            "0 < max_lag_fraction <= 1, 0 <= search_fraction <= 1");
    }
    if (rows == 0 || cols == 0) throw InvalidInput("period check: the capture is empty");
    PeriodCheck check;
    check.tolerance_px = o.tolerance_px;
    const int r = static_cast<int>(rows), c = static_cast<int>(cols);
    // An axis with fewer than two periods is skipped before anything is read.
    auto axis_check = [&](Axis axis, int size, int expected) {
        if (size < 2 * expected) return check_axis(Plane(), axis, size, expected, o);
        return check_axis(strips_across(rows, cols, axis, at), axis, size, expected, o);
    };
    check.rows = axis_check(Axis::kRows, r, expected_rows);
    check.cols = axis_check(Axis::kCols, c, expected_cols);
    // The tolerance the axes applied (the larger, when they differ): what a report should quote.
    for (const AxisPeriodCheck* a : {&check.rows, &check.cols}) {
        if (a->checked) check.tolerance_px = std::max(check.tolerance_px, a->tolerance_px);
    }
    return check;
}

}  // namespace

PeriodCheck check_period(const Plane& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& o) {
    return check_frame(
        capture.rows(), capture.cols(),
        [&](Eigen::Index r, Eigen::Index c) { return capture(r, c); }, expected_rows, expected_cols,
        o);
}

PeriodCheck check_period(const Image& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& o) {
    return check_frame(
        capture.rows(), capture.cols(),
        [&](Eigen::Index r, Eigen::Index c) {
            double v = 0.0;
            for (const Plane& p : capture.channels) v += p(r, c);
            return v;
        },
        expected_rows, expected_cols, o);
}

}  // namespace pinmask
