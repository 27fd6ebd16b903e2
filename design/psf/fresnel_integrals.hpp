// Fresnel integrals, normalised as in Abramowitz & Stegun 7.3:
//   C(x) = int_0^x cos(pi t^2 / 2) dt,   S(x) = int_0^x sin(pi t^2 / 2) dt,   F(x) = C(x) + i S(x).
// F is odd, F(+inf) = (1 + i)/2. The auxiliary functions f, g (A&S 7.3.5-6) give, for x >= 0,
//   F(x) = (1 + i)/2 - G(x) exp(i pi x^2 / 2),   G(x) = g(x) + i f(x),
// with G slowly varying (f ~ 1/(pi x), g ~ 1/(pi^2 x^3) for large x). Differences F(b) - F(a) of
// two large, close arguments are formed from G without cancellation (see
// design/psf/kernel_profile). Method: power series for |x| < 1.5, a continued fraction for the
// complementary error function (modified Lentz) for 1.5 <= |x| < 1e8, the A&S 7.3.27-28 asymptotic
// series beyond. Accuracy is a few ulps of max(|F|, 1) (tests/design/test_fresnel_integrals.cpp).
#pragma once

#include <complex>

namespace pinmask {

// F(x) = C(x) + i S(x) for any finite real x.
std::complex<double> fresnel_cs(double x);

// G(x) = g(x) + i f(x) for x >= 0 (throws InvalidInput for x < 0 or NaN).
std::complex<double> fresnel_aux(double x);

// exp(i pi y) with the argument reduced exactly modulo 2 before multiplying by pi.
std::complex<double> cis_pi(double y);

}  // namespace pinmask
