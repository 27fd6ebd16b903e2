#include <doctest/doctest.h>

#include <cmath>

#include "core/errors/error.hpp"
#include "design/psf/kernel_quadrature.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {
// Nodes from Newton's iteration to ~1 ulp; sums of up to 1000 weighted terms of size <= 1.
constexpr double kRuleTol = 1e-13;
}  // namespace

TEST_CASE("known small rules") {
    const auto r2 = gauss_legendre(2);
    CHECK_CLOSE(r2.nodes[1], 1 / std::sqrt(3.0), kRuleTol);
    CHECK_CLOSE(r2.weights[0], 1.0, kRuleTol);
    const auto r3 = gauss_legendre(3);
    CHECK(r3.nodes[1] == 0.0);
    CHECK_CLOSE(r3.nodes[2], std::sqrt(0.6), kRuleTol);
    CHECK_CLOSE(r3.weights[1], 8.0 / 9.0, kRuleTol);
    CHECK_CLOSE(r3.weights[0], 5.0 / 9.0, kRuleTol);
    const auto r1 = gauss_legendre(1);
    CHECK(r1.nodes[0] == 0.0);
    CHECK_CLOSE(r1.weights[0], 2.0, kRuleTol);
}

TEST_CASE("an m-point rule integrates x^k exactly up to degree 2m - 1, for odd, prime, even m") {
    for (int m : {1, 2, 5, 8, 12, 13, 64, 97, 128}) {
        const auto r = gauss_legendre(m);
        for (int k = 0; k <= 2 * m - 1 && k <= 60; ++k) {
            double s = 0;
            for (int i = 0; i < m; ++i) s += r.weights[i] * std::pow(r.nodes[i], k);
            const double exact = k % 2 ? 0.0 : 2.0 / (k + 1);
            INFO("m = " << m << " k = " << k);
            CHECK(std::fabs(s - exact) <= kRuleTol);
        }
        for (int i = 1; i < m; ++i) CHECK(r.nodes[i] > r.nodes[i - 1]);
    }
    CHECK_THROWS_AS(gauss_legendre(0), InvalidInput);
}

TEST_CASE("panels integrate an oscillating function") {
    const auto r = gauss_legendre(12);
    const double got = integrate_panels(r, 0.0, 40.0, 80, [](double x) { return std::cos(x); });
    CHECK(std::fabs(got - std::sin(40.0)) <= kRuleTol);
}
