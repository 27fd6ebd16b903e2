#include "decode/capture/period.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"

namespace pinmask {
namespace {

// The smallest power of two >= n: the transform sizes FFTW does fastest (measured on the
// bench capture: 4096 points cost about half of 3456 or 5000).
int fft_size(int n) {
    int m = 1;
    while (m < n) m *= 2;
    return m;
}

// Readers of the frame the check reads: add_row(j, lo, len, out) adds columns lo .. lo + len - 1
// of frame row j (contiguous in the row-major Plane: one vectorised pass) to `out`, row_sum(i,
// first, w) is the sum of the w adjacent values of row i from column first. An image reads its
// luminance, the sum of its channels in channel order.
struct PlaneReader {
    const Plane& p;
    double row_sum(Eigen::Index i, Eigen::Index first, Eigen::Index w) const {
        double s = 0.0;
        for (Eigen::Index j = first; j < first + w; ++j) s += p(i, j);
        return s;
    }
    template <class Col>
    void add_row(Eigen::Index j, Eigen::Index lo, Eigen::Index len, Col&& out) const {
        out += p.row(j).segment(lo, len).transpose();
    }
};

struct ImageReader {
    const Image& img;
    double row_sum(Eigen::Index i, Eigen::Index first, Eigen::Index w) const {
        double s = 0.0;
        for (Eigen::Index j = first; j < first + w; ++j) {
            double v = 0.0;
            for (const Plane& p : img.channels) v += p(i, j);
            s += v;
        }
        return s;
    }
    template <class Col>
    void add_row(Eigen::Index j, Eigen::Index lo, Eigen::Index len, Col&& out) const {
        Eigen::ArrayXd sum = img.channels[0].row(j).segment(lo, len).transpose();
        for (std::size_t ch = 1; ch < img.channels.size(); ++ch)
            sum += img.channels[ch].row(j).segment(lo, len).transpose();
        out += sum;
    }
};

// The lines the check reads along the lag axis (`axis`) of a rows x cols frame read through the
// reader `at`: every line across when there are at most kAcrossStrips * kStripWidth of them,
// else `strips` (at most across / kStripWidth) strips of kStripWidth adjacent lines spread
// evenly across the frame, each strip averaged into one line, over the samples lo .. lo + size
// - 1 along the lag axis. A capture periodic along the lag axis gives strips exactly periodic
// with the same period; the early exit reads kAcrossStrips strips over kConfirmPeriods periods
// (a small fraction of a one-period decode's cost), the full search all of the frame in strips.
// The result is size x lines whatever the axis (the lag down each column), its mean removed.
template <class At>
Plane lines_across(Eigen::Index rows, Eigen::Index cols, Axis axis, const At& at,
                   Eigen::Index strips, Eigen::Index lo, Eigen::Index size) {
    const Eigen::Index across = axis == Axis::kRows ? cols : rows;
    const bool all = across <= Eigen::Index{kAcrossStrips} * kStripWidth;
    const Eigen::Index n = all ? across : std::min(strips, across / kStripWidth);
    const Eigen::Index w = all ? 1 : kStripWidth;
    Plane out = Plane::Zero(size, n);
    // Strip k is centred on (k + 1/2) across / n.
    std::vector<Eigen::Index> first(static_cast<std::size_t>(n));
    for (Eigen::Index k = 0; k < n; ++k) {
        first[std::size_t(k)] =
            all ? k
                : std::clamp<Eigen::Index>((2 * k + 1) * across / (2 * n) - w / 2, 0, across - w);
    }
    if (axis == Axis::kRows) {
        // Each frame row once, all its strips (w adjacent values each): one pass down the frame.
        for (Eigen::Index i = 0; i < size; ++i)
            for (Eigen::Index k = 0; k < n; ++k)
                out(i, k) = at.row_sum(lo + i, first[std::size_t(k)], w);
    } else {
        // Frame rows first .. first + w - 1, each contiguous: summed a row at a time.
        Eigen::ArrayXd sum(size);
        for (Eigen::Index k = 0; k < n; ++k) {
            sum.setZero();
            for (Eigen::Index j = first[std::size_t(k)]; j < first[std::size_t(k)] + w; ++j)
                at.add_row(j, lo, size, sum);
            out.col(k) = sum;
        }
    }
    if (w > 1) out /= static_cast<double>(w);
    out -= out.mean();
    return out;
}

// Pearson normalisation of the lag sums of lines x (size x n, lag down the columns): with
// e(i) = sum_k x(i, k)^2 and E its running sum (E[j] = sum_{i < j} e(i)), the energies of the
// two overlapping parts at lag d are head(d) = E[size - d] and tail(d) = E[size] - E[d].
struct OverlapEnergy {
    std::vector<double> cumulative;  // E, size + 1 entries
    double head(int d) const { return cumulative[cumulative.size() - 1 - std::size_t(d)]; }
    double tail(int d) const { return cumulative.back() - cumulative[std::size_t(d)]; }
    // rho(d) from the lag sum a(d); 0 when either part has no energy (a constant part).
    double rho(double a, int d) const {
        const double h = head(d), t = tail(d);
        return h > 0.0 && t > 0.0 ? a / std::sqrt(h * t) : 0.0;
    }
};

OverlapEnergy overlap_energy(const Plane& x) {
    OverlapEnergy e;
    e.cumulative.assign(static_cast<std::size_t>(x.rows()) + 1, 0.0);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        e.cumulative[std::size_t(i) + 1] =
            e.cumulative[std::size_t(i)] + x.row(i).matrix().squaredNorm();
    return e;
}

// rho(d) of lines (mean removed) by direct sums over the overlapping pairs, each lag computed
// once. The sums run in single precision (the lines copied once): twice the SIMD width, and the
// values are only compared with each other at the 1e-2 level (a relative rounding of ~1e-6 over a
// few thousand products cannot move a decision).
class DirectLags {
  public:
    DirectLags(const Plane& x, const OverlapEnergy& e) : x_(x.cast<float>()), e_(e) {}
    double operator()(int d) {
        for (const auto& [lag, v] : done_)
            if (lag == d) return v;
        const Eigen::Index m = x_.rows() - d;
        double a = 0.0;
        for (Eigen::Index k = 0; k < x_.cols(); ++k)
            a += double(x_.col(k).head(m).dot(x_.col(k).segment(d, m)));
        done_.emplace_back(d, e_.rho(a, d));
        return done_.back().second;
    }

  private:
    Eigen::MatrixXf x_;
    const OverlapEnergy& e_;
    std::vector<std::pair<int, double>> done_;
};

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

// The first local maximum of the profile in 2 .. max_lag whose rise over the lowest value at
// smaller lags (from lag 1) is at least min_rise, refined; empty when there is none.
std::optional<ProfilePeak> first_repeat(const std::vector<double>& p, int max_lag,
                                        double min_rise) {
    const int n = static_cast<int>(p.size());
    max_lag = std::min(max_lag, n - 2);
    double left_min = n > 1 ? p[1] : 0.0;
    for (int d = 2; d <= max_lag; ++d) {
        left_min = std::min(left_min, p[static_cast<std::size_t>(d - 1)]);
        const double here = p[static_cast<std::size_t>(d)];
        if (here >= p[static_cast<std::size_t>(d - 1)] &&
            here > p[static_cast<std::size_t>(d + 1)] && here - left_min >= min_rise) {
            return refine(p, d, here - left_min);
        }
    }
    return std::nullopt;
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

// The lag sums a(d) = sum_k sum_i x(i, k) x(i + d, k), d = 0 .. last, of lines x (size x n, lag
// down the columns), by FFTs zero-padded to size + last samples down the columns (no lag up to
// `last` wraps around). The lines' power spectra are summed before the one inverse transform:
// the 2-D transform X(f, l) of the padded lines gives sum_k |X_k(f)|^2 = (1 / n) sum_l |X(f,
// l)|^2 (Parseval across the lines), the half-spectrum's missing l > n / 2 read as |X(-f, n -
// l)|^2; a 1-D inverse of length pr then replaces the 2-D one (half the transform work).
std::vector<double> lag_sums(const Plane& x, int last) {
    const int size = static_cast<int>(x.rows()), n = static_cast<int>(x.cols());
    const int pr = fft_size(size + last);
    check_memory(double(pr) * n * 8.0 * 3.0, "the autocorrelation of the capture");
    Plane padded = Plane::Zero(pr, n);
    padded.topRows(size) = x;
    const Fft2 fft(pr, n);
    const ComplexPlane spectrum = fft.forward(padded);
    // l = 0 and (n even) l = n / 2 are their own mirror; 1 .. (n - 1) / 2 stand for two.
    const int paired = (n - 1) / 2;
    Eigen::ArrayXd own = spectrum.col(0).abs2(), pairs = Eigen::ArrayXd::Zero(pr);
    if (n % 2 == 0 && n > 1) own += spectrum.col(n / 2).abs2();
    for (int l = 1; l <= paired; ++l) pairs += spectrum.col(l).abs2();
    ComplexPlane power(pr, 1);
    for (int f = 0; f < pr; ++f)
        power(f, 0) = (own(f) + pairs(f) + pairs((pr - f) % pr)) / double(n);
    const Plane acf = Fft2(pr, 1).inverse(power);
    std::vector<double> a(static_cast<std::size_t>(last + 1));
    for (int d = 0; d <= last; ++d) a[static_cast<std::size_t>(d)] = acf(d, 0);
    return a;
}

// rho(d) from the lag sums and the overlap energies (OverlapEnergy); rho(0) = 1, and 0 past it
// for lines without energy (constant: nothing repeats).
std::vector<double> normalised(const std::vector<double>& a, const OverlapEnergy& e) {
    std::vector<double> profile(a.size(), 0.0);
    profile[0] = 1.0;
    if (!(e.cumulative.back() > 0.0)) return profile;
    for (std::size_t d = 1; d < a.size(); ++d) profile[d] = e.rho(a[d], static_cast<int>(d));
    return profile;
}

// rho(d), d = 0 .. last (max_lag < 0: size - 1), of lines x (size x n, mean removed).
std::vector<double> lag_profile(const Plane& x, int max_lag) {
    const int size = static_cast<int>(x.rows());
    const int last = max_lag < 0 ? size - 1 : std::min(max_lag, size - 1);
    return normalised(lag_sums(x, last), overlap_energy(x));
}

// Lines x minus their centred moving average over `width` samples down each column (fewer at
// the ends, where the window is cut), then the mean removed (kHighPassFraction).
Plane high_passed(const Plane& x, int width) {
    const Eigen::Index size = x.rows(), half = width / 2;
    Plane out(size, x.cols());
    std::vector<double> c(static_cast<std::size_t>(size) + 1);
    for (Eigen::Index k = 0; k < x.cols(); ++k) {
        c[0] = 0.0;
        for (Eigen::Index i = 0; i < size; ++i) c[std::size_t(i) + 1] = c[std::size_t(i)] + x(i, k);
        for (Eigen::Index i = 0; i < size; ++i) {
            const Eigen::Index lo = std::max<Eigen::Index>(0, i - half),
                               hi = std::min(size, i + half + 1);
            out(i, k) = x(i, k) - (c[std::size_t(hi)] - c[std::size_t(lo)]) / double(hi - lo);
        }
    }
    out -= out.mean();
    return out;
}

// The full search's profile of lines x (size x n), kept per contiguous block of lines
// (kUncertaintyGroups; fewer when there are fewer lines) so a lag can be measured in each block
// alone; the whole profile is the blocks' sums normalised by their summed energies.
struct BlockProfiles {
    std::vector<std::vector<double>> sums;  // a_g(d) per block
    std::vector<OverlapEnergy> energy;      // per block
    std::vector<double> whole;              // rho(d) of all the lines

    BlockProfiles(const Plane& x, int last) {
        const Eigen::Index n = x.cols();
        const Eigen::Index blocks = std::min<Eigen::Index>(kUncertaintyGroups, n);
        std::vector<double> total(static_cast<std::size_t>(last + 1), 0.0);
        OverlapEnergy all;
        all.cumulative.assign(static_cast<std::size_t>(x.rows()) + 1, 0.0);
        for (Eigen::Index g = 0; g < blocks; ++g) {
            const Eigen::Index lo = g * n / blocks, hi = (g + 1) * n / blocks;
            const Plane part = x.middleCols(lo, hi - lo);
            sums.push_back(lag_sums(part, last));
            energy.push_back(overlap_energy(part));
            for (std::size_t d = 0; d < total.size(); ++d) total[d] += sums.back()[d];
            for (std::size_t i = 0; i < all.cumulative.size(); ++i)
                all.cumulative[i] += energy.back().cumulative[i];
        }
        whole = normalised(total, all);
    }
    std::vector<double> block(std::size_t g) const { return normalised(sums[g], energy[g]); }
};

// The early exit: the repeat tested at the expected lag P alone, by direct sums on a few lags
// of the lines x (size x n, mean removed). Accepted (the peak returned) only when
//   (a) the lags from P walking uphill reach a local maximum of rho within w = ceil(tolerance)
//       + 1 of P, and the parabola through it and its neighbours is within the tolerance of P;
//   (b) its rise over the lowest of the valley lags (P / 4, P / 3, P / 2, 3P / 4, rounded) is
//       at least min_rise, as in the full search, and its value at least kConfirmMinValue (a
//       noise bump near P, with the true repeat outside the window, has neither);
//   (c) no fraction of P repeats as well: rho at P / 2 and P / 3 (rounded down and up) rises by
//       less than kConfirmSubharmonic of the peak's rise (a capture repeating at P / k also
//       repeats at P: that is the full search's to report, kFundamentalFraction);
//   (d) P is not part of a longer repeat: the rise at 2P is at most the peak's over
//       kConfirmMultiple (a capture repeating every 2P may half-repeat at P); 2P must be
//       within max_lag.
// Anything else returns nothing and the full search decides (it reports a mismatch with both
// figures, so its cost then does not matter). The valley estimated from a few lags is never
// lower than the profile's minimum, so the rise tested is a lower bound of the full search's.
std::optional<ProfilePeak> confirm_expected(const Plane& x, const OverlapEnergy& energy,
                                            int expected, double tolerance, double min_rise,
                                            int max_lag) {
    const int w = static_cast<int>(std::ceil(tolerance)) + 1;
    if (expected - w < 2 || 2 * expected + 1 > max_lag || !(energy.cumulative.back() > 0.0))
        return std::nullopt;
    DirectLags rho(x, energy);
    // (a) uphill from P to a local maximum, at most w lags away.
    int d = expected;
    const int step = rho(d + 1) > rho(d) ? 1 : (rho(d - 1) > rho(d) ? -1 : 0);
    while (step != 0 && rho(d + step) > rho(d)) {
        d += step;
        if (std::abs(d - expected) >= w) return std::nullopt;  // rising past the window
    }
    ProfilePeak peak = refine({rho(d - 1), rho(d), rho(d + 1)}, 1, 0.0);
    peak.lag += d - 1;
    if (!(std::fabs(peak.lag - expected) <= tolerance)) return std::nullopt;
    // (b) the valley.
    double low = peak.value, sub = -std::numeric_limits<double>::infinity();
    for (int j : {1, 3}) low = std::min(low, rho((j * expected + 2) / 4));
    for (int k : {2, 3}) {
        for (int lag : {expected / k, (expected + k - 1) / k}) {
            low = std::min(low, rho(lag));
            sub = std::max(sub, rho(lag));
        }
    }
    peak.rise = peak.value - low;
    if (!(peak.rise >= min_rise) || !(peak.value >= kConfirmMinValue)) return std::nullopt;
    // (c) and (d).
    if (!(sub - low < kConfirmSubharmonic * peak.rise)) return std::nullopt;
    if (!(kConfirmMultiple * (rho(2 * expected) - low) <= peak.rise)) return std::nullopt;
    return peak;
}

// One view of the full search (kHighPassFraction): the repeat chosen, whether it came from the
// fundamental rule, and its precision (kUncertaintyGroups, kMismatchSignificance).
struct ViewResult {
    std::optional<ProfilePeak> chosen;
    bool fundamental = false;
    double uncertainty = std::numeric_limits<double>::infinity();
    double significance = std::numeric_limits<double>::infinity();
    int high_pass = 0;
};

ViewResult search_view(const Plane& lines, int high_pass, int expected, int max_lag,
                       const PeriodCheckOptions& o) {
    ViewResult r;
    r.high_pass = high_pass;
    // Lags up to max_lag + 1: the searches compare each lag with its right neighbour.
    const BlockProfiles blocks(high_pass > 0 ? high_passed(lines, high_pass) : lines, max_lag + 1);
    // A high-passed profile dips below 0 at lags under the width even for noise (the filter's own
    // negative lobe: -1/3 for a width of 3), and the rise out of that dip is no repeat: there the
    // profile is read clipped at 0, so a rise is a repeat's correlation above none.
    const auto view = [high_pass](std::vector<double> p) {
        if (high_pass > 0)
            for (double& v : p) v = std::max(v, 0.0);
        return p;
    };
    const std::vector<double> profile = view(blocks.whole);
    const auto best = strongest_repeat(profile, max_lag, o.min_rise);
    // A capture that repeats at P also repeats at every multiple, and a pattern may nearly
    // repeat at a fraction of P: what the decoder needs is a repeat at P itself, so the peak
    // near the expected lag is taken when it is as strong as a repeat (same rule as the
    // subharmonics)...
    const int window = std::max(2, static_cast<int>(std::ceil(o.search_fraction * expected)));
    auto near = repeat_near(profile, expected, window, max_lag);
    if (near &&
        (near->rise < o.min_rise || (best && near->rise < kSubharmonicFraction * best->rise))) {
        near.reset();
    }
    // ... unless a smaller lag repeats about as well (kFundamentalFraction): then the capture
    // repeats with that shorter period (the PSF's is a multiple of it), which is reported.
    if (near) {
        const int below = static_cast<int>(std::floor(near->lag)) - window;
        if (const auto f = first_repeat(profile, below, kFundamentalFraction * near->rise)) {
            near = f;
            r.fundamental = true;
        }
    }
    r.chosen = near ? near : best;
    if (!r.chosen) return r;
    // The lag in each block alone, searched as the whole's was (within the window around the
    // expected lag, or around the lag chosen when that lies outside it: searching only next to
    // the whole's peak would hide how far a broad peak's maximum wanders), and each block's
    // rho(measured) - rho(expected).
    const int lag = static_cast<int>(std::lround(r.chosen->lag));
    const int centre = std::abs(lag - expected) <= window ? expected : lag;
    std::vector<double> lags, diffs;
    for (std::size_t g = 0; g < blocks.sums.size(); ++g) {
        const std::vector<double> p = view(blocks.block(g));
        if (const auto q = repeat_near(p, centre, window, max_lag)) lags.push_back(q->lag);
        diffs.push_back(p[std::size_t(lag)] - p[std::size_t(expected)]);
    }
    const auto mean_sd = [](const std::vector<double>& v) {
        double m = 0.0, ss = 0.0;
        for (double x : v) m += x;
        m /= double(v.size());
        for (double x : v) ss += (x - m) * (x - m);
        return std::pair{m, std::sqrt(ss / double(v.size() - 1))};
    };
    if (lags.size() >= 3) r.uncertainty = mean_sd(lags).second;
    if (diffs.size() >= 2) {
        const auto [m, sd] = mean_sd(diffs);
        const double se = sd / std::sqrt(double(diffs.size()));
        r.significance =
            se > 0.0 ? m / se : (m > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    }
    return r;
}

template <class ReadAll>
AxisPeriodCheck check_axis(const Plane& lines, const ReadAll& read_all, Axis axis, int size,
                           int expected, const PeriodCheckOptions& o) {
    AxisPeriodCheck a;
    a.size_px = size;
    a.expected_px = expected;
    const char* name = axis == Axis::kRows ? "rows" : "columns";
    if (size < 2 * expected) {
        a.skip_reason = "the capture holds " + format_cell(double(size) / expected, "%.2f") +
                        " periods along the " + name + " (" + std::to_string(size) + " / " +
                        std::to_string(expected) + " px); a repeat needs at least 2";
        return a;
    }
    if (!is_all_finite(lines)) {
        throw InvalidInput(std::string("period check: the capture holds NaN or Inf in the ") +
                           name + " it reads");
    }
    a.checked = true;
    a.tolerance_px = std::max(o.tolerance_px, o.relative_tolerance * expected);
    const int max_lag = std::min(size - 2, static_cast<int>(std::floor(size * o.max_lag_fraction)));
    const int span = static_cast<int>(lines.rows());
    const int confirm_max_lag =
        std::min(span - 2, static_cast<int>(std::floor(span * o.max_lag_fraction)));
    ViewResult kept;
    kept.chosen = confirm_expected(lines, overlap_energy(lines), expected, a.tolerance_px,
                                   o.min_rise, confirm_max_lag);
    a.early_exit = kept.chosen.has_value();
    if (!a.early_exit) {
        // The full search reads strips over the whole frame (kFullSearchStrips), in both
        // views; the more precise one is kept (the lines as read on a tie).
        const Plane all = read_all();
        if (!is_all_finite(all)) {
            throw InvalidInput(std::string("period check: the capture holds NaN or Inf in the ") +
                               name + " it reads");
        }
        const int width = static_cast<int>(kHighPassFraction * expected) | 1;
        kept = search_view(all, 0, expected, max_lag, o);
        if (width >= kMinHighPassWidth) {
            ViewResult v = search_view(all, width, expected, max_lag, o);
            if (v.chosen && (!kept.chosen || v.uncertainty < kept.uncertainty)) kept = v;
        }
    }
    if (!kept.chosen) {
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
    a.found = true;
    a.measured_px = kept.chosen->lag;
    a.peak_value = kept.chosen->value;
    a.peak_rise = kept.chosen->rise;
    a.within_tolerance = std::fabs(kept.chosen->lag - expected) <= a.tolerance_px;
    if (!a.early_exit) {
        a.high_pass_px = kept.high_pass;
        a.uncertainty_px = kept.uncertainty;
        a.significance = kept.significance;
    }
    a.matches =
        a.within_tolerance ||
        (a.early_exit ? false : !kept.fundamental && kept.significance < kMismatchSignificance);
    return a;
}

}  // namespace

std::vector<double> autocorrelation_profile(const Plane& x, Axis axis, int max_lag) {
    if (x.size() == 0) throw InvalidInput("autocorrelation: the plane is empty");
    if (!is_all_finite(x)) throw InvalidInput("autocorrelation: the plane holds NaN or Inf");
    // The lag down the columns of `lines` (size x lines), mean removed.
    const Plane lines =
        axis == Axis::kRows ? Plane(x - x.mean()) : Plane((x - x.mean()).transpose());
    return lag_profile(lines, max_lag);
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
        const auto read_all = [&] {
            const Eigen::Index across = axis == Axis::kRows ? cols : rows;
            return lines_across(rows, cols, axis, at,
                                std::min<Eigen::Index>(kFullSearchStrips, across / kStripWidth), 0,
                                size);
        };
        if (size < 2 * expected) return check_axis(Plane(), read_all, axis, size, expected, o);
        // The early exit's lines: the centred kConfirmPeriods periods (the whole side if fewer).
        const int span = static_cast<int>(
            std::min<long long>(size, static_cast<long long>(kConfirmPeriods) * expected));
        return check_axis(
            lines_across(rows, cols, axis, at, kAcrossStrips, (size - span) / 2, span), read_all,
            axis, size, expected, o);
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
    return check_frame(capture.rows(), capture.cols(), PlaneReader{capture}, expected_rows,
                       expected_cols, o);
}

PeriodCheck check_period(const Image& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& o) {
    return check_frame(capture.rows(), capture.cols(), ImageReader{capture}, expected_rows,
                       expected_cols, o);
}

}  // namespace pinmask
