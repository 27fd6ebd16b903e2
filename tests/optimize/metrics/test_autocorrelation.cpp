#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "core/errors/error.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/autocorrelation.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_pattern.hpp"

using namespace pinmask;
using pinmask::test::random_pattern;

namespace {

// O(n^4) reference: R(d) = sum_x o(x) o(x + d) over the torus.
std::vector<int> direct_autocorrelation(const Pattern& p) {
    const int n = p.n;
    std::vector<int> o(static_cast<std::size_t>(n) * n, 0), r(o.size(), 0);
    for (const Cell& c : p.pinholes) o[c.row * n + c.col] = 1;
    for (int dr = 0; dr < n; ++dr)
        for (int dc = 0; dc < n; ++dc)
            for (int x = 0; x < n; ++x)
                for (int y = 0; y < n; ++y)
                    r[dr * n + dc] += o[x * n + y] * o[((x + dr) % n) * n + (y + dc) % n];
    return r;
}

}  // namespace

TEST_CASE("autocorrelation from the spectrum equals the direct count (odd, prime, 2^k sizes)") {
    for (int n : {1, 2, 5, 7, 13, 16, 31}) {
        for (int k : {1, std::max(1, n * n / 8), std::max(1, n * n / 2)}) {
            const Pattern p = random_pattern(n, k, 100u * n + k);
            INFO("n " << n << " K " << k);
            const std::vector<int> r = autocorrelation_from_spectrum(pattern_spectrum(p));
            CHECK(r == direct_autocorrelation(p));
            CHECK(r[0] == k);
        }
    }
}

TEST_CASE("sidelobe metrics by hand") {
    // Two pinholes at (0,0), (0,1) on a 3 x 3 torus: R = 2 at 0, 1 at (0,1) and (0,2).
    Pattern p;
    p.n = 3;
    p.pinholes = {{0, 0}, {0, 1}};
    const SidelobeMetrics m = sidelobe_metrics_from_spectrum(pattern_spectrum(p));
    CHECK(m.peak == 2);
    CHECK(m.max_sidelobe == 1);
    CHECK(m.mean_sidelobe == doctest::Approx(2.0 / 8.0));
    CHECK(m.integrated_sidelobe_level == doctest::Approx(2.0 / 4.0));
    CHECK(m.peak_to_sidelobe_ratio == doctest::Approx(2.0));
    // The mean sidelobe is K (K - 1) / (n^2 - 1) for every pattern.
    const Pattern q = random_pattern(11, 17, 9);
    CHECK(sidelobe_metrics_from_spectrum(pattern_spectrum(q)).mean_sidelobe ==
          doctest::Approx(17.0 * 16.0 / 120.0));
    // A single pinhole has no sidelobes at all.
    Pattern one;
    one.n = 4;
    one.pinholes = {{1, 2}};
    const SidelobeMetrics s = sidelobe_metrics_from_spectrum(pattern_spectrum(one));
    CHECK(s.max_sidelobe == 0);
    CHECK(std::isinf(s.peak_to_sidelobe_ratio));
    CHECK_THROWS_AS(sidelobe_metrics({0, 1, 1, 1}, 2), InvalidInput);
    CHECK_THROWS_AS(sidelobe_metrics({1, 1, 1}, 2), InvalidInput);
}

TEST_CASE("a (16, 6, 2) difference set in Z4 x Z4 has every sidelobe equal to 2") {
    // Exhaustive search over the C(16, 6) = 8008 subsets for one whose nonzero differences each
    // occur exactly lambda = 2 times.
    Pattern found;
    bool ok = false;
    for (int mask = 0; mask < (1 << 16) && !ok; ++mask) {
        if (__builtin_popcount(mask) != 6) continue;
        Pattern p;
        p.n = 4;
        for (int i = 0; i < 16; ++i)
            if (mask & (1 << i)) p.pinholes.push_back({i / 4, i % 4});
        const std::vector<int> r = direct_autocorrelation(p);
        ok = std::all_of(r.begin() + 1, r.end(), [](int v) { return v == 2; });
        if (ok) found = p;
    }
    REQUIRE(ok);
    const SidelobeMetrics m = sidelobe_metrics_from_spectrum(pattern_spectrum(found));
    CHECK(m.peak == 6);
    CHECK(m.max_sidelobe == 2);
    CHECK(m.mean_sidelobe == doctest::Approx(2.0));
    CHECK(m.peak_to_sidelobe_ratio == doctest::Approx(3.0));
    CHECK(m.integrated_sidelobe_level == doctest::Approx(15.0 * 4.0 / 36.0));
}
