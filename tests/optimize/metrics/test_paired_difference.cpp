// Differences between masks' figures and their standard errors
// (optimize/metrics/paired_difference): hand-computed cases, and the median's standard error
// against the asymptotic value of two populations whose density at the median is known.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/errors/error.hpp"
#include "optimize/metrics/paired_difference.hpp"

using namespace pinmask;

TEST_CASE("paired difference: mean, standard error of the mean, two-SE significance") {
    // d = (1, 2, 4): mean 7/3, sd^2 = ((4/3)^2 + (1/3)^2 + (5/3)^2) / 2 = 7/3, SE = sqrt(7)/3.
    const PairedDifference d = paired_difference({11.0, 12.0, 14.0}, {10.0, 10.0, 10.0});
    CHECK(d.difference == doctest::Approx(7.0 / 3.0).epsilon(1e-15));
    CHECK(d.standard_error == doctest::Approx(std::sqrt(7.0) / 3.0).epsilon(1e-15));
    CHECK(d.samples == 3);
    CHECK_FALSE(d.exact);
    CHECK(d.significant);  // 2.33 >= 2 x 0.88
    // d = (1, -1, 1.5): mean 0.5, SE = sqrt(1.75 / 3) = 0.764: under two SE.
    const PairedDifference n = paired_difference({1.0, -1.0, 1.5}, {0.0, 0.0, 0.0});
    CHECK(n.difference == doctest::Approx(0.5).epsilon(1e-15));
    CHECK(n.standard_error == doctest::Approx(std::sqrt(1.75 / 3.0)).epsilon(1e-15));
    CHECK_FALSE(n.significant);
    // A constant shift has no spread: exactly known from the samples.
    const PairedDifference c = paired_difference({2.0, 3.0}, {1.0, 2.0});
    CHECK(c.standard_error == 0.0);
    CHECK(c.significant);
    // One sample: no spread known, never significant.
    const PairedDifference one = paired_difference({5.0}, {1.0});
    CHECK(one.difference == 4.0);
    CHECK(std::isnan(one.standard_error));
    CHECK_FALSE(one.significant);
    CHECK_THROWS_AS(paired_difference({1.0}, {1.0, 2.0}), InvalidInput);
    CHECK_THROWS_AS(paired_difference({}, {}), InvalidInput);
}

TEST_CASE("exact difference: closed-form figures have no sampling error") {
    const PairedDifference d = exact_difference(21.5, 21.25);
    CHECK(d.difference == 0.25);
    CHECK(d.standard_error == 0.0);
    CHECK(d.exact);
    CHECK(d.significant);
    CHECK_FALSE(exact_difference(3.0, 3.0).significant);
}

TEST_CASE("median: the lower median and the order statistics' standard error") {
    CHECK(median_estimate({3.0, 1.0, 2.0, 4.0}).median == 2.0);  // the baseline's median draw
    CHECK(std::isnan(median_estimate({7.0}).standard_error));
    CHECK_THROWS_AS(median_estimate({}), InvalidInput);
    // 1..100: j = floor(50 - 9.80) = 40, k = ceil(51 + 9.80) = 61, SE = 21 / 3.92.
    std::vector<double> grid;
    for (int i = 1; i <= 100; ++i) grid.push_back(i);
    CHECK(median_estimate(grid).standard_error ==
          doctest::Approx(21.0 / (2.0 * 1.959963984540054)).epsilon(1e-12));
    // Large samples: SE -> 1 / (2 f(median) sqrt(S)); normal: sqrt(pi / 2) sigma / sqrt(S),
    // uniform on [0, 1]: 1 / (2 sqrt(S)). The estimate scatters by a few % at S = 20000.
    constexpr int kS = 20000;
    constexpr double kScatter = 0.1;
    std::mt19937_64 rng(5);
    std::normal_distribution<double> normal(3.0, 2.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<double> a, b;
    for (int i = 0; i < kS; ++i) {
        a.push_back(normal(rng));
        b.push_back(uniform(rng));
    }
    const double root = std::sqrt(static_cast<double>(kS));
    CHECK(median_estimate(a).standard_error ==
          doctest::Approx(std::sqrt(std::numbers::pi / 2.0) * 2.0 / root).epsilon(kScatter));
    CHECK(median_estimate(b).standard_error == doctest::Approx(0.5 / root).epsilon(kScatter));
}
