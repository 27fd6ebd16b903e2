#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/errors/error.hpp"
#include "optimize/metrics/nsr_tuning.hpp"

using namespace pinmask;

TEST_CASE("golden section finds the minimum of a unimodal function to the tolerance") {
    const double tol = 1e-6;
    const ScalarMinimum m = golden_section_minimise(
        [](double x) { return (x - 0.3) * (x - 0.3) + 2.0; }, -1.0, 2.0, tol);
    CHECK(std::fabs(m.x - 0.3) <= tol);
    CHECK(m.value == doctest::Approx(2.0));
    // Bracket shrinks by 0.618 per evaluation: log(3 / 1e-6) / log(1.618) = 31, plus 4 setup.
    CHECK(m.evaluations <= 36);
}

TEST_CASE("minimum at an end point and NaN values") {
    const ScalarMinimum m = golden_section_minimise([](double x) { return x; }, 1.0, 4.0, 1e-3);
    CHECK(m.x == 1.0);
    const ScalarMinimum n = golden_section_minimise(
        [](double x) { return x > 2.0 ? std::numeric_limits<double>::quiet_NaN() : -x; }, 0.0, 3.0,
        1e-3);
    CHECK(n.x <= 2.0);
    CHECK(n.x >= 2.0 - 2e-3);
    CHECK_THROWS_AS(golden_section_minimise([](double x) { return x; }, 1.0, 1.0, 1e-3),
                    InvalidInput);
}

TEST_CASE("log-scale weight tuning") {
    const ScalarMinimum m =
        tune_log_weight([](double w) { return std::pow(std::log10(w) + 2.3, 2) + 1.0; });
    CHECK(std::fabs(std::log10(m.x) + 2.3) <= kTuneToleranceLog10);
}
