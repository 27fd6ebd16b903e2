// Period of a capture, measured from its autocorrelation, and the check against the PSF's size.
//
// A cyclic mask seen by a sensor larger than one period gives a capture that repeats with the
// image-plane period (docs/design.md section 2: p = d [(1 - f/f') + f/u] per cell). If the object is
// nearer than designed, or the sensor pitch or distances differ from the mask file, the capture
// repeats with another period than the PSF's and a decode with that PSF is wrong; this check
// measures the period so the mismatch can be reported, never hidden.
//
// Notation: x the capture (mean removed), R x C its size. The linear (zero-padded)
// autocorrelation along the rows is a(d) = sum_{r, c} x(r, c) x(r + d, c), d = 0 .. R - 1 (the
// sum runs over the (R - d) C overlapping pairs), likewise along the columns. The normalised
// profile is the correlation of the two overlapping parts, rho(d) = a(d) / sqrt(H(d) T(d)) with
// H(d) = sum_{r < R - d, c} x(r, c)^2 and T(d) = sum_{r >= d, c} x(r, c)^2 their energies: 1 at
// d = 0, 1 again at a lag where the capture repeats exactly, and below 1 at every other lag
// (Cauchy-Schwarz). Normalising each lag by its own overlap's energies (not by the mean square
// of the whole frame) keeps the repeat's peak at its lag on a window of a few periods, where the
// energy of the overlap changes with the lag (a 1100 px window of a 336 px period measured 333).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

enum class Axis { kRows, kCols };

// rho(d) for d = 0 .. size - 1 along `axis` (rows: vertical lag), computed with FFTs zero-padded
// to size + the last lag; max_lag >= 0 stops at that lag (fewer samples to transform).
// Throws InvalidInput for an empty or non-finite plane. A constant plane (or an overlap without
// energy) gives rho = 0 past d = 0.
std::vector<double> autocorrelation_profile(const Plane& x, Axis axis, int max_lag = -1);

// A peak of the profile: the lag refined to sub-pixel by a parabola through the three samples
// around the integer maximum, the profile's value there, and its rise over the lowest value at
// smaller lags (the valley that separates it from the central lobe).
struct ProfilePeak {
    double lag = 0.0;
    double value = 0.0;
    double rise = 0.0;
};

// The repeat lag of a profile, searched in 2 .. max_lag: among the local maxima, the one with the
// largest rise over the preceding valley; a smaller lag whose rise is at least
// kSubharmonicFraction of that wins (so 2P is not reported for P). Empty when no local maximum
// rises by at least min_rise.
std::optional<ProfilePeak> strongest_repeat(const std::vector<double>& profile, int max_lag,
                                            double min_rise);

// A peak at lag P is accompanied by one at 2P of similar height; noise can make 2P the larger.
// Lags whose rise is at least this fraction of the best are treated as the same repeat.
inline constexpr double kSubharmonicFraction = 0.7;

// The peak at the expected lag P is reported only if no shorter lag repeats about as well: the
// first lag whose rise reaches this fraction of P's is reported instead (a capture that repeats
// every P / 2 also repeats every P, and a PSF of twice its period is still the wrong one).
// Valid captures of coded masks rise at P / 2 by at most ~0.7 of P (so they are not reported
// as "half the period"); an exact repeat at P / 2 rises as much as P, noise making it ~0.95 ..
// 1.05.
inline constexpr double kFundamentalFraction = 0.9;

// The early exit (decode/capture/period.cpp, confirm_expected): before any search, rho is summed
// directly at the lags around the expected P, at P / 4, P / 3, P / 2, 3P / 4 and 2P. P is
// accepted at once when its peak lies within the tolerance, reaches kConfirmMinValue and rises
// by at least min_rise, P / 2
// and P / 3 rise by less than kConfirmSubharmonic of it (well below kFundamentalFraction, so no
// capture the full search would report as repeating at a fraction of P is accepted) and 2P
// rises by at most 1 / kConfirmMultiple of it (a capture repeating every 2P rises at P by
// about half as much). Anything doubtful falls through to the full search over every lag.
inline constexpr double kConfirmSubharmonic = 0.7;
inline constexpr double kConfirmMultiple = 0.8;
// The early exit also needs rho at P of at least this: the repeat explains at least half the
// variance of the lines read (a noise bump near P reaches ~0.2 on a short sharp tile; a capture
// whose repeat is weaker than its noise goes to the full search, which reads every line).
inline constexpr double kConfirmMinValue = 0.5;
// The early exit reads its strips over the centred kConfirmPeriods periods of the lag axis (the
// whole side when shorter): lags up to 2P keep 2P overlapping samples, and on a 6-period sensor
// a third less is read and summed.
inline constexpr int kConfirmPeriods = 4;

// What the check reads, along each axis: strips of kStripWidth adjacent lines, each averaged
// into one line (every line when the frame has at most kAcrossStrips * kStripWidth across). The
// early exit reads kAcrossStrips strips spread evenly across the frame, over kConfirmPeriods
// periods along the lag axis: ~64 lines, a small fraction of a one-period decode's cost
// (`pinmask bench period`). The full search, taken only when the early exit doubts, reads up
// to kFullSearchStrips strips spread over the whole frame. A repeat along the lag axis is exact
// in every strip. Values outside what is read are not
// checked (decode checks the frame for NaN/Inf first).
inline constexpr int kAcrossStrips = 8;
inline constexpr int kStripWidth = 8;
// The full search reads at most this many strips spread across the frame (every line of a
// 1024-line frame, half the lines of a 2048-line one). 256 strips cost 3.4x the time on the
// bench capture (0.072 s against 0.022 s, 2048 x 2448) and decided no capture of the tests
// differently: a weak repeat is settled by its significance (kMismatchSignificance), not by
// reading more lines.
inline constexpr int kFullSearchStrips = 128;

// The full search looks at the lines twice: as read, and high-passed along the lag axis (each
// line minus its centred moving average over kHighPassFraction of the expected period, rounded
// to an odd width >= 3). A linear shift-invariant filter keeps any repeat at its lag; the
// high-pass removes what is smooth on that scale -- the falling light of an exact-geometry
// capture's partly lit edge periods, a low-contrast scene's broad correlation -- which bends a
// broad peak and moved its parabola 0.7 - 2.3 px off on captures simulated with exact geometry
// (paper camera, letter-R and natural scenes). The view whose lag is the more precise is kept.
inline constexpr double kHighPassFraction = 0.25;
// The high-passed view is taken only for widths of at least this (expected periods >= 36 px):
// the filter's own correlation at lags between half its width and its width is (width - d) /
// width^2, which for white noise reaches 0.17 at a width of 3 (a false repeat at 2 px) and
// stays under 0.06 from 9 up, below min_rise.
inline constexpr int kMinHighPassWidth = 9;
// The precision of a view's lag: the lines are split into kUncertaintyGroups contiguous blocks
// across the frame, the repeat is measured in each block alone (searched as the whole's is), and
// the standard deviation of the block lags is the lag's uncertainty. It is the spread of a lag
// measured on an eighth of the frame, so it bounds the whole's error generously (the whole's
// lag is the maximum of a noisy profile, not the blocks' mean: on the C-mount camera's natural
// scene at 10 dB the whole measured 162 px for 169 with a standard error of 1.2 px).
inline constexpr int kUncertaintyGroups = 8;
// A lag outside the tolerance is a mismatch only if the capture repeats at it significantly
// better than at the expected lag: per block, rho(measured) - rho(expected); the mean of the
// block differences over its standard error (a t statistic with blocks - 1 degrees of freedom)
// must reach this. 5 is beyond the 0.999 quantile of t with 7 degrees of freedom (4.8): a weak
// repeat at the noise (a natural scene at 10 dB: rho ~ 0.07 over a peak 20 px wide, measured
// 130 px for 128) is then reported as consistent, with its uncertainty, not as a mismatch. A
// capture that repeats at a fraction of the expected period (the fundamental rule above) is a
// mismatch whatever the statistic: it repeats at the expected lag too.
inline constexpr double kMismatchSignificance = 5.0;

struct PeriodCheckOptions {
    // |measured - expected| allowed is the larger of these: half a pixel (beyond it the period
    // rounds to another integer), and 0.5 % of the period: the sub-pixel estimate of a broad
    // peak on a long period wanders by a few tenths of a pixel, and a pitch off by 1 % or more
    // (the size worth reporting) must still fail by a clear margin.
    double tolerance_px = 0.5;
    double relative_tolerance = 0.005;
    // The repeat is looked for within +-max(2 px, this fraction of the expected period) of it
    // before the strongest repeat anywhere is taken: 5 % holds every pitch error up to 5 %.
    double search_fraction = 0.05;
    // Smallest rise of the profile peak over its valley for a repeat to count as found: a
    // capture of an exactly periodic pattern rises by ~1; 0.1 sits well above the fluctuations
    // of rho for a non-repeating capture of a few hundred pixels per side.
    double min_rise = 0.1;
    // Largest lag searched, as a fraction of the side: beyond 2/3 fewer than a third of the
    // rows (columns) overlap and rho gets noisy.
    double max_lag_fraction = 2.0 / 3.0;
};

// The check along one axis.
struct AxisPeriodCheck {
    int size_px = 0;           // capture side along this axis
    int expected_px = 0;       // PSF side along this axis
    bool checked = false;      // false: skipped, see skip_reason
    std::string skip_reason;   // why it was skipped (empty when checked)
    bool found = false;        // a repeat was found (checked only)
    double measured_px = 0.0;  // the repeat lag (found only)
    double peak_value = 0.0;   // rho at the repeat (found only)
    double peak_rise = 0.0;    // the peak's rise over its valley (found only)
    bool early_exit = false;   // accepted at the expected lag by the direct test (no search)
    // Full search only (found, not early_exit): the view kept (0: the lines as read, else the
    // high-pass width in px), the uncertainty of measured_px (kUncertaintyGroups; infinity when
    // fewer than 3 blocks found a repeat) and the t statistic of rho(measured) - rho(expected)
    // over the blocks (kMismatchSignificance; infinity when the blocks agree exactly).
    int high_pass_px = 0;
    double uncertainty_px = 0.0;
    double significance = 0.0;
    bool within_tolerance = false;  // found and |measured - expected| <= tolerance_px
    // found, and within the tolerance or not significantly off (kMismatchSignificance): the
    // capture is consistent with the PSF's period.
    bool matches = false;
    double tolerance_px = 0.0;  // max(options.tolerance_px, relative_tolerance * expected)
};

struct PeriodCheck {
    AxisPeriodCheck rows, cols;
    double tolerance_px = 0.0;
    bool checked() const { return rows.checked || cols.checked; }
    // True when every checked axis found its repeat at the expected period.
    bool matches() const {
        return (!rows.checked || rows.matches) && (!cols.checked || cols.matches);
    }
};

// Measures the capture's period along each axis and compares it with the expected (PSF) size:
// first the early exit at the expected lag (kConfirmMinValue .. kConfirmPeriods); when it
// doubts, the profile of the whole frame's strips in both views (kHighPassFraction), in each the
// repeat near the expected lag when it is as strong as the strongest repeat
// (kSubharmonicFraction) and no shorter lag repeats about as well (kFundamentalFraction), else
// the strongest; the view with the smaller uncertainty is kept, and a lag outside the tolerance
// is a mismatch when it is significant (kMismatchSignificance).
// An axis is skipped (with the reason) when the capture holds fewer than two periods along it
// (a single period has no repeat to measure), or when no repeat rises above min_rise at all
// (nothing to compare: not a contradiction of the PSF). Throws InvalidInput for an empty
// capture, non-finite values in the lines read, an expected size < 1 or options out of range.
PeriodCheck check_period(const Plane& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& options = {});
// The same on the luminance (sum of the channels) of an image, read only in the strips.
PeriodCheck check_period(const Image& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& options = {});

}  // namespace pinmask
