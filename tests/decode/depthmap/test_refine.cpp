// decode/depthmap/refine against closed forms: the vertex of a parabola sampled at three planes,
// the ends of the sweep, and the confidence formula.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/errors/error.hpp"
#include "decode/depthmap/refine.hpp"
#include "decode/depthmap/sweep_cost.hpp"

using namespace pinmask;

namespace {
std::vector<Plane> costs_of(const std::vector<double>& c) {
    std::vector<Plane> out;
    for (double v : c) out.push_back(Plane::Constant(1, 1, v));
    return out;
}
}  // namespace

TEST_CASE("refine_depth puts the depth at the vertex of the parabola through three planes") {
    // Planes at 1/u = 2, 1.5, 1, 0.5 /m; cost (x - 1.2)^2 + 0.1 in x = 1/u: vertex at 1/u = 1.2.
    const std::vector<double> inv{2.0, 1.5, 1.0, 0.5};
    std::vector<double> c;
    for (double x : inv) c.push_back((x - 1.2) * (x - 1.2) + 0.1);
    const RefinedDepth r = refine_depth(costs_of(c), inv);
    CHECK(r.label(0, 0) == 2.0);
    CHECK(r.depth_m(0, 0) == doctest::Approx(1.0 / 1.2).epsilon(1e-12));
    // Median of the 4 costs (the upper middle, as nth_element at K/2): sorted 0.14, 0.19, 0.59,
    // 0.74 -> 0.59; confidence (0.59 - 0.14) / 0.59.
    CHECK(r.confidence(0, 0) == doctest::Approx((0.59 - 0.14) / 0.59).epsilon(1e-12));
}

TEST_CASE("refine_depth keeps the end plane and refuses unordered planes") {
    const std::vector<double> inv{1.0, 0.5, 0.0};  // the last plane at infinity
    RefinedDepth r = refine_depth(costs_of({3.0, 2.0, 1.0}), inv);
    CHECK(r.label(0, 0) == 2.0);
    CHECK(std::isinf(r.depth_m(0, 0)));
    r = refine_depth(costs_of({1.0, 2.0, 3.0}), inv);
    CHECK(r.depth_m(0, 0) == doctest::Approx(1.0));
    CHECK_THROWS_AS(refine_depth(costs_of({1.0, 2.0, 3.0}), {1.0, 0.5, 0.7}), InvalidInput);
}

TEST_CASE("box_mean equals the direct cyclic sum") {
    Plane p(5, 7);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 7; ++j) p(i, j) = std::sin(1.3 * i + 0.7 * j * j);
    const Plane b = box_mean(p, 3);
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 7; ++j) {
            double s = 0;
            for (int a = -1; a <= 1; ++a)
                for (int c = -1; c <= 1; ++c) s += p((i + a + 5) % 5, (j + c + 7) % 7);
            CHECK(b(i, j) == doctest::Approx(s / 9.0).epsilon(1e-12));
        }
    }
}
