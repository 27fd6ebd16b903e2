// Period of a capture, measured from its autocorrelation, and the check against the PSF's size.
//
// A cyclic mask seen by a sensor larger than one period gives a capture that repeats with the
// image-plane period (DESIGN.md section 1: p = d [(1 - f/f') + f/u] per cell). If the object is
// nearer than designed, or the sensor pitch or distances differ from the mask file, the capture
// repeats with another period than the PSF's and a decode with that PSF is wrong; this check
// measures the period so the mismatch can be reported, never hidden.
//
// Notation: x the capture (mean removed), R x C its size. The linear (zero-padded)
// autocorrelation along the rows is a(d) = sum_{r, c} x(r, c) x(r + d, c), d = 0 .. R - 1 (the
// sum runs over the (R - d) C overlapping pairs), likewise along the columns. The normalised
// profile is rho(d) = [a(d) / ((R - d) C)] / [a(0) / (R C)]: the mean product at lag d over the
// mean square, 1 at d = 0 and 1 again at a lag where the capture repeats exactly.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/image.hpp"

namespace pinmask {

enum class Axis { kRows, kCols };

// rho(d) for d = 0 .. size - 1 along `axis` (rows: vertical lag), computed with FFTs zero-padded
// to size + the last lag; max_lag >= 0 stops at that lag (fewer samples to transform).
// Throws InvalidInput for an empty or non-finite plane. A constant plane gives rho = 0 past d = 0.
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

// What the check reads: along each axis, kAcrossStrips strips of kStripWidth adjacent lines
// spread evenly across the frame (every line when the frame has at most kAcrossStrips *
// kStripWidth across), each strip averaged into one line; the profile is the sum of the strips'
// autocorrelations. A repeat along the lag axis is exact in every strip, and reading ~64 lines
// instead of the frame keeps the cost a small fraction of a one-period decode's (`pinmask bench
// period`; 8 strips of 8 cost about half of 16 of 4, whose 16-wide transforms plan badly). Values
// outside the strips are not read (decode checks the frame for NaN/Inf first).
inline constexpr int kAcrossStrips = 8;
inline constexpr int kStripWidth = 8;

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
    int size_px = 0;            // capture side along this axis
    int expected_px = 0;        // PSF side along this axis
    bool checked = false;       // false: skipped, see skip_reason
    std::string skip_reason;    // why it was skipped (empty when checked)
    bool found = false;         // a repeat was found (checked only)
    double measured_px = 0.0;   // the repeat lag (found only)
    double peak_value = 0.0;    // rho at the repeat (found only)
    double peak_rise = 0.0;     // the peak's rise over its valley (found only)
    bool matches = false;       // found and |measured - expected| <= tolerance_px
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
// the profile of the strips (kAcrossStrips, kStripWidth), the repeat near the expected
// lag when it is as strong as the strongest repeat (kSubharmonicFraction), else the strongest.
// An axis is skipped (with the reason) when the capture holds fewer than two periods along it
// (a single period has no repeat to measure), or when no repeat rises above min_rise at all
// (nothing to compare: not a contradiction of the PSF). Throws InvalidInput for an empty
// capture, non-finite values in the strips read, an expected size < 1 or options out of range.
PeriodCheck check_period(const Plane& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& options = {});
// The same on the luminance (sum of the channels) of an image, read only in the strips.
PeriodCheck check_period(const Image& capture, int expected_rows, int expected_cols,
                         const PeriodCheckOptions& options = {});

}  // namespace pinmask
