// optimize/search/rerank_order: a candidate moves above another only when its simulated PSNR is
// higher by more than the standard error of the paired per-scene difference; the objective's order
// stands otherwise. The standard errors here are worked by hand.
#include <doctest/doctest.h>

#include <vector>

#include "optimize/search/rerank_order.hpp"

using pinmask::rerank_order;
using pinmask::simulated_clearly_better;

TEST_CASE("re-rank order: differences within their standard error keep the objective's order") {
    // b - a per scene: +0.3, -0.1, +0.1: mean 0.1, sd = sqrt((0.04 + 0.04 + 0) / 2) = 0.2,
    // SE = 0.2 / sqrt(3) = 0.1155 > 0.1: not clearly better.
    const std::vector<double> a{20.0, 21.0, 22.0}, b{20.3, 20.9, 22.1};
    CHECK_FALSE(simulated_clearly_better(b, a));
    CHECK(rerank_order({a, b}) == std::vector<std::size_t>{0, 1});
    // A 0.001 dB edge on every scene but one: mean 0.0005, sd 0.000577, SE 0.000289 < mean:
    // consistent across scenes, so it counts (the rule is about noise, not size).
    const std::vector<double> c{20.001, 21.001, 22.0, 22.0};
    const std::vector<double> a4{20.0, 21.0, 22.0, 22.0};
    CHECK(simulated_clearly_better(c, a4));
}

TEST_CASE("re-rank order: clear differences reorder; ties and noise do not") {
    // b - a = +1.0, +0.8, +1.2: mean 1.0, sd 0.2, SE 0.115: b clearly better.
    const std::vector<double> a{20.0, 21.0, 22.0}, b{21.0, 21.8, 23.2};
    CHECK(simulated_clearly_better(b, a));
    CHECK_FALSE(simulated_clearly_better(a, b));
    // c is a within noise (above); the order a, c, b becomes b, a, c: b passes both.
    const std::vector<double> c{20.3, 20.9, 22.1};
    CHECK(rerank_order({a, c, b}) == std::vector<std::size_t>{2, 0, 1});
    // Equal figures never move.
    CHECK(rerank_order({a, a, a}) == std::vector<std::size_t>{0, 1, 2});
    // One scene: any positive difference counts (no spread to judge it by).
    CHECK(simulated_clearly_better({20.1}, {20.0}));
    CHECK_FALSE(simulated_clearly_better({20.0}, {20.0}));
    CHECK_THROWS(simulated_clearly_better({1.0, 2.0}, {1.0}));
}
