// decode/calibrate/grid_read against closed forms: a polynomial of degree 5 is reproduced to
// rounding, and a sinusoid of the phone camera's fringe spacing (6.6 nodes per period) keeps its
// value within 0.5 % of its amplitude everywhere between the nodes, where the bilinear read is
// 11 % off at half a node.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "decode/calibrate/grid_read.hpp"

using namespace pinmask;

TEST_CASE("grid read: 6-point Lagrange weights reproduce polynomials to degree 5") {
    auto f = [](double v, double u) {
        return 0.3 + 0.1 * u - 0.02 * v * v + 1e-3 * u * u * u * v - 2e-5 * std::pow(u, 5) +
               3e-5 * std::pow(v, 4) * u;
    };
    calibrate::GridF g(12, 14);
    for (int v = 0; v < 12; ++v)
        for (int u = 0; u < 14; ++u) g(v, u) = static_cast<float>(f(v, u));
    for (double v : {2.0, 2.5, 4.31, 7.99, 8.0})
        for (double u : {2.0, 3.7, 6.25, 10.5}) {
            CAPTURE(v);
            CAPTURE(u);
            CHECK(calibrate::read_lagrange6(g, v, u) ==
                  doctest::Approx(f(v, u)).epsilon(1e-5).scale(1.0));
        }
    double w[6];
    calibrate::lagrange6_weights(0.5, w);
    const double half[6] = {3 / 256.0,   -25 / 256.0, 150 / 256.0,
                            150 / 256.0, -25 / 256.0, 3 / 256.0};
    for (int k = 0; k < 6; ++k) CHECK(w[k] == doctest::Approx(half[k]).epsilon(1e-14));
}

TEST_CASE("grid read: a fringe of 6.6 nodes per period between the nodes") {
    const double k = 2 * std::numbers::pi / 6.6;
    calibrate::GridF g(10, 40);
    for (int v = 0; v < 10; ++v)
        for (int u = 0; u < 40; ++u) g(v, u) = static_cast<float>(std::cos(k * u + 0.4));
    double worst = 0.0;
    for (double u = 2.0; u < 36.0; u += 0.05)
        worst =
            std::max(worst, std::abs(calibrate::read_lagrange6(g, 4.5, u) - std::cos(k * u + 0.4)));
    CHECK(worst < 5e-3);
    CHECK(worst > 1e-4);  // an interpolation, not the closed form itself
}
