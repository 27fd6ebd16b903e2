#include <doctest/doctest.h>

#include <cmath>
#include <complex>

#include "core/errors/error.hpp"
#include "design/psf/fresnel_integrals.hpp"
#include "tests/design/test_kernel_reference.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using pinmask::test::kLdPi;
using pinmask::test::ld_integrate;

namespace {

// |F| <= 0.78; the series, continued fraction and phase evaluation each round a handful of times
// on O(1) values, and the long double reference is ~1e-18: a few ulps of 1 with margin.
constexpr double kFresnelAbsTol = 2e-15;
// A&S asymptotic series (3 terms) against the continued fraction: next term below 1e-20 relative
// for x >= 50, so the comparison is limited by the continued fraction's own ~1e-15. Relative in
// the complex sense |G - G_ref| / |G_ref|: g = Re G is ~1/(pi x^2) of |G| and carries only the
// absolute accuracy of G, which is all the kernel needs (it forms |G(t1) - G(t2) e^{i phi}|).
constexpr double kAuxAsymptoticRelTol = 1e-14;

std::complex<double> reference_fresnel(double x) {
    const long long panels = static_cast<long long>(kLdPi * x * x / 2) + 4;
    using C = std::complex<long double>;
    const C f = ld_integrate<C>(0.0L, x, panels, [](long double t) {
        const long double ph = kLdPi * t * t / 2;
        return C(std::cos(ph), std::sin(ph));
    });
    return {static_cast<double>(f.real()), static_cast<double>(f.imag())};
}

// A&S 7.3.27-28 to three terms: G = g + i f.
std::complex<double> asymptotic_aux(double x) {
    const double u = 1.0 / (M_PI * x * x), u2 = u * u;
    const double f = (1 / (M_PI * x)) * (1 - 3 * u2 + 105 * u2 * u2 - 10395 * u2 * u2 * u2);
    const double g =
        (1 / (M_PI * M_PI * x * x * x)) * (1 - 15 * u2 + 945 * u2 * u2 - 135135 * u2 * u2 * u2);
    return {g, f};
}

}  // namespace

TEST_CASE("C and S match a long double quadrature on both sides of the method switch") {
    for (double x : {1e-9, 1e-3, 0.1, 0.5, 1.0, 1.25, 1.4999999, 1.5,  1.5000001, 1.7,
                     2.0,  2.5,  3.0, 4.2, 5.0, 7.5,  10.0,      13.3, 20.0,      31.0}) {
        const auto got = fresnel_cs(x);
        const auto ref = reference_fresnel(x);
        INFO("x = " << x << " got " << got << " ref " << ref);
        CHECK(std::abs(got.real() - ref.real()) <= kFresnelAbsTol);
        CHECK(std::abs(got.imag() - ref.imag()) <= kFresnelAbsTol);
    }
}

TEST_CASE("F is odd, starts like x and tends to (1 + i)/2") {
    for (double x : {0.3, 1.5, 4.0, 1e3}) CHECK(fresnel_cs(-x) == -fresnel_cs(x));
    CHECK(fresnel_cs(0.0) == std::complex<double>(0.0, 0.0));
    CHECK_CLOSE(fresnel_cs(1e-12).real(), 1e-12, 1e-15);
    for (double x : {1e4, 1e7, 1e9}) {
        // |F - (1+i)/2| = |G| ~ 1/(pi x) (beyond ~1e9 it drowns in the rounding of 0.5).
        const double dev = std::abs(fresnel_cs(x) - std::complex<double>(0.5, 0.5));
        CHECK_CLOSE(dev, 1 / (M_PI * x), 1e-6);
    }
    CHECK(fresnel_cs(INFINITY) == std::complex<double>(0.5, 0.5));
}

TEST_CASE("auxiliary G matches its definition below 1.5 and the asymptotic series above") {
    for (double x : {0.0, 0.2, 1.0, 1.49, 1.5, 2.0, 6.0}) {
        const auto ref = reference_fresnel(x);
        const auto g_ref = (std::complex<double>(0.5, 0.5) - ref) * std::conj(cis_pi(x * x / 2));
        INFO("x = " << x);
        CHECK(std::abs(fresnel_aux(x) - g_ref) <= kFresnelAbsTol);
    }
    for (double x : {50.0, 100.0, 1e3, 1e5, 9.9e7, 1.01e8, 1e12}) {
        const auto got = fresnel_aux(x), ref = asymptotic_aux(x);
        INFO("x = " << x << " got " << got << " ref " << ref);
        CHECK(std::abs(got - ref) <= kAuxAsymptoticRelTol * std::abs(ref));
    }
    CHECK_THROWS_AS(fresnel_aux(-1.0), InvalidInput);
}

TEST_CASE("cis_pi reduces its argument exactly") {
    CHECK(std::abs(cis_pi(1e15 + 0.5) - std::complex<double>(0, 1)) < 1e-15);
    CHECK(std::abs(cis_pi(-3.0) - std::complex<double>(-1, 0)) < 1e-15);
    CHECK(std::abs(cis_pi(0.25) - std::polar(1.0, M_PI / 4)) < 1e-15);
}
