// One-dimensional tuning of a regularisation weight (the Wiener NSR, a TV lambda) by
// golden-section search on its base-10 logarithm.
#pragma once

#include <functional>

namespace pinmask {

struct ScalarMinimum {
    double x = 0.0;      // the argument of the smallest value found
    double value = 0.0;  // f(x)
    int evaluations = 0;
};

// Golden-section search for the minimum of f on [lo, hi] (lo < hi, finite; InvalidInput
// otherwise). Exact for a unimodal f up to `tolerance` in x (> 0); also returns the best of the
// evaluated points (the end points included) when f is not unimodal. NaN values count as +inf.
ScalarMinimum golden_section_minimise(const std::function<double(double)>& f, double lo, double hi,
                                      double tolerance);

// Search range and resolution for weights tuned on a log scale, in decades.
inline constexpr double kTuneMinLog10 = -7.0;
inline constexpr double kTuneMaxLog10 = 1.0;
inline constexpr double kTuneToleranceLog10 = 0.01;  // ~2 %: below what the error curve resolves

// Minimises error(weight) over weight = 10^t, t in [kTuneMinLog10, kTuneMaxLog10]; the result's
// x is the weight itself (not its logarithm).
ScalarMinimum tune_log_weight(const std::function<double(double weight)>& error);

}  // namespace pinmask
