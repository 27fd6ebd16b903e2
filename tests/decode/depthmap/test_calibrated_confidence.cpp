// decode/depthmap/calibrated_confidence: the knots are a non-decreasing map into [0, 1], the map
// passes through them, is linear between them (the midpoint written here) and clamped outside.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "decode/depthmap/calibrated_confidence.hpp"

using namespace pinmask;

TEST_CASE("calibrated_confidence: a non-decreasing piecewise-linear map through its knots") {
    const auto& k = kMarginProbabilityKnots;
    for (std::size_t i = 0; i < k.size(); ++i) {
        CHECK(k[i].second >= 0.0);
        CHECK(k[i].second <= 1.0);
        CHECK(margin_probability(k[i].first) == doctest::Approx(k[i].second).epsilon(1e-15));
        if (i > 0) {
            CHECK(k[i].first > k[i - 1].first);
            CHECK(k[i].second >= k[i - 1].second);
            const double mid = 0.5 * (k[i].first + k[i - 1].first);
            CHECK(margin_probability(mid) ==
                  doctest::Approx(0.5 * (k[i].second + k[i - 1].second)).epsilon(1e-12));
        }
    }
    CHECK(margin_probability(0.0) == k.front().second);
    CHECK(margin_probability(-1.0) == k.front().second);
    CHECK(margin_probability(std::numeric_limits<double>::quiet_NaN()) == k.front().second);
    CHECK(margin_probability(1.0) == k.back().second);
    Plane m(1, 3);
    m << 0.0, 0.2, 1.0;
    const Plane c = calibrated_confidence(m);
    for (int j = 0; j < 3; ++j) CHECK(c(0, j) == margin_probability(m(0, j)));
}
