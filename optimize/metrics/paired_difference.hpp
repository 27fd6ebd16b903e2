// How far one mask's figure is from another's, and whether the difference is evidence.
//
// Simulated figures (a mean over scenes): paired over the scenes, the same scenes and noise draws
// for both masks, d_s = b(s) - a(s) (each scene's figure already averaged over its noise seeds);
// the difference is mean(d) and its standard error sd(d) / sqrt(S), sd with S - 1. One scene
// gives no spread: the standard error is unknown (NaN) and the difference is not called
// significant. A difference under two standard errors is not significant.
// Analytic figures (closed form over the prior): the difference is exact (standard error 0).
//
// A median of a sample (the random baseline's median mask) estimates the population's median;
// its standard error from the distribution-free 95 % interval of the order statistics: with the
// sorted x_(1) <= ... <= x_(S), j = floor(S/2 - 1.96 sqrt(S)/2), k = ceil(S/2 + 1 + 1.96
// sqrt(S)/2) (clipped to 1..S), SE = (x_(k) - x_(j)) / (2 x 1.96). For a normal sample it
// tends to the asymptotic sqrt(pi/2) sigma / sqrt(S).
#pragma once

#include <vector>

namespace pinmask {

inline constexpr double kSignificantStandardErrors = 2.0;

struct PairedDifference {
    double difference = 0.0;      // b - a
    double standard_error = 0.0;  // 0 when exact, NaN when unknown (one sample)
    int samples = 0;              // paired samples (scenes); 0 when exact
    bool exact = false;           // a closed-form figure: no sampling error
    bool significant = false;     // exact and non-zero, or |difference| >= 2 standard errors
};

// b - a paired over the samples (both the same size, >= 1; InvalidInput otherwise).
PairedDifference paired_difference(const std::vector<double>& b, const std::vector<double>& a);

// b - a of two closed-form figures.
PairedDifference exact_difference(double b, double a);

struct MedianEstimate {
    double median = 0.0;          // the lower median x_((S + 1) / 2) (the baseline's median draw)
    double standard_error = 0.0;  // the rule above; NaN for one value
};

// The lower median of `values` (>= 1; InvalidInput otherwise) and its standard error (NaN for
// fewer than 2 values).
MedianEstimate median_estimate(std::vector<double> values);

}  // namespace pinmask
