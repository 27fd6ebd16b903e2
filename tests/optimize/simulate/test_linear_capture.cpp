// optimize/simulate/simulate linear_capture (the exact-geometry forward model) against a direct
// O(N^2) sum of its definition, on odd and even sizes.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>

#include "core/errors/error.hpp"
#include "optimize/simulate/simulate.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::random_plane;

namespace {

// FFT convolution of O(1) values on a few hundred samples: rounding ~1e-15 relative.
constexpr double kFftTol = 1e-12;

}  // namespace

TEST_CASE("linear_capture equals the direct sum of its definition") {
    for (const auto& [mr, mc, R, C] :
         {std::array{5, 4, 13, 11}, std::array{8, 8, 16, 24}, std::array{7, 3, 7, 9}}) {
        const Plane x = random_plane(mr, mc, 1), w = random_plane(R, C, 2);
        const Plane c = linear_capture(x, w);
        REQUIRE(c.rows() == R);
        REQUIRE(c.cols() == C);
        double worst = 0;
        for (int r = 0; r < R; ++r) {
            for (int k = 0; k < C; ++k) {
                double direct = 0;
                for (int i = 0; i < mr; ++i) {
                    for (int j = 0; j < mc; ++j) {
                        const int wr = r - i + mr / 2, wc = k - j + mc / 2;
                        if (wr >= 0 && wr < R && wc >= 0 && wc < C) direct += x(i, j) * w(wr, wc);
                    }
                }
                worst = std::max(worst, std::fabs(c(r, k) - direct));
            }
        }
        CHECK(worst <= kFftTol * mr * mc);
    }
    Plane bad = random_plane(3, 3, 1);
    bad(1, 1) = NAN;
    CHECK_THROWS_AS(linear_capture(bad, random_plane(5, 5, 2)), InvalidInput);
}
