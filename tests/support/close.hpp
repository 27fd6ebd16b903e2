// The one shared close-compare helper of the test suites. Every tolerance passed to it has a name
// and a reason at its definition.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

namespace pinmask::test {

// |a - b| <= tol * max(|a|, |b|, floor): relative, with an absolute floor for values near zero.
inline bool close_rel(double a, double b, double tol, double floor = 1e-300) {
    const double scale = std::max({std::fabs(a), std::fabs(b), floor});
    return std::fabs(a - b) <= tol * scale;
}

// Relative error of an array against a reference: max|a - ref| / max|ref|.
template <class A, class B>
double max_rel_error(const A& a, const B& ref) {
    const double denom = std::max(static_cast<double>((ref).abs().maxCoeff()), 1e-300);
    return static_cast<double>(((a) - (ref)).abs().maxCoeff()) / denom;
}

}  // namespace pinmask::test

// CHECK_CLOSE(a, b, tol): relative comparison, printing both values and the tolerance on failure.
#define CHECK_CLOSE(a, b, tol)                                                    \
    do {                                                                          \
        const double pm_a_ = (a), pm_b_ = (b);                                    \
        INFO(#a " = " << pm_a_ << ", " #b " = " << pm_b_ << ", tol = " << (tol)); \
        CHECK(::pinmask::test::close_rel(pm_a_, pm_b_, (tol)));                   \
    } while (0)
