#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/errors/error.hpp"
#include "design/psf/kernel_profile.hpp"
#include "design/psf/kernel_quadrature.hpp"
#include "tests/design/test_kernel_reference.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using pinmask::test::kLdPi;
using pinmask::test::ld_integrate;
using pinmask::test::reference_profile;

namespace {

// j_l(x) <= 1. Upward recurrence near l ~ x and Miller's normalisation each lose a few ulps.
constexpr double kBesselAbsTol = 1e-14;
// h is compared against the brute-force long double integral relative to its peak value
// max(1, 1/(4N)) scale (1 for small N): the evaluation forms |J|^2 from O(1) sums.
constexpr double kProfileTol = 2e-13;
// The two forms are independent; both are within kProfileTol of the truth.
constexpr double kFormsAgreeTol = 4e-13;

double reference_bessel(int l, double x) {
    // j_l(x) = (-i)^l / 2 int P_l(s) exp(i x s) ds: even l -> cos, odd l -> sin.
    const long long panels = static_cast<long long>(2 * x + l) + 4;
    const long double sum = ld_integrate<long double>(-1.0L, 1.0L, panels, [&](long double s) {
        long double p0 = 1, p1 = s;
        if (l == 0) p1 = 1;
        for (int k = 2; k <= l; ++k) {
            const long double p2 = ((2 * k - 1) * s * p1 - (k - 1) * p0) / k;
            p0 = p1;
            p1 = p2;
        }
        return p1 * (l % 2 == 0 ? std::cos(x * s) : std::sin(x * s));
    });
    const int sign = ((l / 2) % 2 == 0) ? 1 : -1;
    return static_cast<double>(sign * sum / 2);
}

}  // namespace

TEST_CASE("spherical Bessel functions: closed forms and quadrature, both recurrence branches") {
    for (double x : {1e-9, 0.01, 0.7, 1.0, 3.3, 12.0}) {
        const auto j = spherical_bessel_j(2, x);
        const double s = std::sin(x), c = std::cos(x);
        if (x >= 0.5) {
            CHECK(std::fabs(j[0] - s / x) <= kBesselAbsTol);
            CHECK(std::fabs(j[1] - (s / (x * x) - c / x)) <= kBesselAbsTol);
            CHECK(std::fabs(j[2] - ((3 / (x * x) - 1) * s / x - 3 * c / (x * x))) <= kBesselAbsTol);
        } else {
            const double x2 = x * x;  // series to the term below 1e-12 relative at x = 0.01
            CHECK_CLOSE(j[0], 1 - x2 / 6 + x2 * x2 / 120, 1e-12);
            CHECK_CLOSE(j[1], x / 3 - x * x2 / 30 + x * x2 * x2 / 840, 1e-12);
        }
    }
    const int l_max = 80;
    for (double x : {1e-6, 0.3, 2.0, 17.0, 40.0, 79.5, 80.5, 150.0, 400.5}) {
        const auto j = spherical_bessel_j(l_max, x);
        for (int l : {0, 1, 2, 3, 10, 31, 40, 60, 79, 80}) {
            INFO("l = " << l << " x = " << x);
            CHECK(std::fabs(j[l] - reference_bessel(l, x)) <= kBesselAbsTol);
        }
    }
    CHECK(spherical_bessel_j(5, 0.0)[0] == 1.0);
    CHECK(spherical_bessel_j(5, 0.0)[3] == 0.0);
    CHECK_THROWS_AS(spherical_bessel_j(3, -1.0), InvalidInput);
}

TEST_CASE("integral form matches brute force for 0 <= N <= 4") {
    for (double n : {0.0, 1e-4, 0.01, 0.3, 0.87, 1.0, 2.0, 4.0}) {
        const FresnelProfile h(n);
        for (double v : {0.0, 0.3, 1.0, 2.5, 7.7, 30.0, 100.3, 500.5}) {
            INFO("N = " << n << " v = " << v);
            CHECK(std::fabs(h.integral_form(v) - reference_profile(n, v)) <= kProfileTol);
        }
    }
}

TEST_CASE("closed form matches brute force from N = 1e-4 to 300, inside and in the shadow") {
    // The brute-force reference costs ~N; N = 300 is sampled at a few points only (the limits
    // test below covers N = 1e4 against the box).
    for (double n : {1e-4, 1e-2, 0.5, 1.0, 10.0, 100.0, 300.0}) {
        const FresnelProfile h(n);
        const double scale = std::max(1.0, 1.0 / (4 * n));  // no larger than the peak
        const std::vector<double> fractions =
            n > 100 ? std::vector<double>{0.5, 1.0}
                    : std::vector<double>{0.0, 0.2, 0.9, 0.999, 1.0, 1.001, 1.1, 3.0};
        for (double f : fractions) {
            for (double v : {f * 2 * n, f * 2 * n + 0.37, f * 2 * n + 41.3}) {
                INFO("N = " << n << " v = " << v);
                CHECK(std::fabs(h.closed_form(v) - reference_profile(n, v)) <= kProfileTol * scale);
            }
        }
    }
}

TEST_CASE("the two forms agree where both apply, so the switch at N = 1 is seamless") {
    for (double n : {0.05, 0.2, 0.6, 0.999, 1.0, 1.001, 1.7, 4.0}) {
        const FresnelProfile h(n);
        for (double v = 0.0; v < 60.0; v += 0.173) {
            INFO("N = " << n << " v = " << v);
            CHECK(std::fabs(h.integral_form(v) - h.closed_form(v)) <= kFormsAgreeTol);
        }
    }
    const FresnelProfile below(kFresnelFormSwitch * (1 - 1e-13));
    const FresnelProfile above(kFresnelFormSwitch * (1 + 1e-13));
    for (double v = 0.0; v < 30.0; v += 0.31) CHECK(std::fabs(below(v) - above(v)) <= 1e-12);
}

TEST_CASE("limits: N = 0 is sinc^2, small N approaches it as N^2, large N approaches the box") {
    const FresnelProfile zero(0.0);
    for (double v : {0.0, 0.5, 1.0, 3.25, 77.0}) {
        CHECK(std::fabs(zero(v) - fraunhofer_profile(v)) <= 1e-15);
    }
    CHECK(fraunhofer_profile(0.5) == doctest::Approx(4 / (M_PI * M_PI)).epsilon(1e-15));
    for (double n : {1e-4, 1e-3, 1e-2}) {
        const FresnelProfile h(n);
        // First-order terms cancel (m2 is real): |h - sinc^2| <= (pi N)^2 (|m2|^2 + |m4|) / 4,
        // with |m2| <= 2/3, |m4| <= 2/5.
        const double bound = std::pow(M_PI * n, 2) * (4.0 / 9 + 0.4) / 4;
        for (double v = 0; v < 50; v += 0.37) {
            CHECK(std::fabs(h(v) - fraunhofer_profile(v)) <= bound);
        }
    }
    for (double n : {1e2, 1e3, 1e4}) {
        const FresnelProfile h(n);
        // Well inside the spot the edge waves have amplitude ~ 1/(pi t) with t >= sqrt(2N)/2:
        // |h - 1/(4N)| / (1/(4N)) <= 2 * 2 / (pi sqrt(2N) / 2) + its square.
        const double rel = 8 / (M_PI * std::sqrt(2 * n));
        for (double f : {0.0, 0.25, 0.5}) {
            CHECK(std::fabs(h(f * 2 * n) * 4 * n - 1) <= rel * (1 + rel));
        }
        // Far outside it falls like the edge-wave intensity.
        CHECK(h(4 * n) * 4 * n < 1e-3);
    }
}

TEST_CASE("normalisation: int h dv = 1 up to the 1/v^2 tail") {
    const auto rule = gauss_legendre(12);
    const double big_v = 400;
    for (double n : {0.0, 0.5, 0.87, 3.0, 20.0}) {
        const FresnelProfile h(n);
        const double inside =
            2 * integrate_panels(rule, 0.0, big_v, static_cast<int>(2 * big_v), h);
        // Tail beyond V: two edge waves of intensity ~ 1/(2 pi^2 v^2) each (plus their
        // interference, zero on average): 2 * int_V^inf 1/(pi^2 v^2) dv = 2/(pi^2 V) to leading
        // order; allow 50% for the next order.
        const double tail = 1 - inside;
        INFO("N = " << n << " tail = " << tail);
        CHECK(tail >= 0);
        CHECK(tail <= 1.5 * 1 / (M_PI * M_PI * (big_v - 2 * n)));
    }
}

TEST_CASE("no NaN or Inf anywhere; symmetric in v and in the sign of N") {
    for (double n = 1e-4; n <= 1e4; n *= 3.7) {
        const FresnelProfile h(n), hm(-n);
        for (double v : {0.0, 1e-9, 0.5, 2 * n, 2 * n * (1 + 1e-15), 1e3, 1e6, 1e9}) {
            const double a = h(v);
            INFO("N = " << n << " v = " << v);
            CHECK(std::isfinite(a));
            CHECK(a >= 0);
            CHECK(h(-v) == a);
            CHECK(hm(v) == a);
        }
    }
    CHECK_THROWS_AS(FresnelProfile(NAN), InvalidInput);
    CHECK_THROWS_AS(FresnelProfile(10.0).integral_form(1.0), InvalidInput);
}
