#include "design/psf/fresnel_integrals.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// Below this the power series converges fast with little cancellation (largest term ~ 7 at 1.5);
// above it the continued fraction converges in at most ~60 steps (Numerical Recipes' choice).
constexpr double kSeriesMax = 1.5;
// Above this two terms of the asymptotic series are exact to rounding (next term ~ 1e-31).
constexpr double kAsymptoticMin = 1e8;
constexpr int kMaxIterations = 1000;

// F(x) = x sum_k (i pi x^2 / 2)^k / (k! (2k + 1)), for 0 <= x < kSeriesMax.
Complex series(double x) {
    const double q = 0.5 * kPi * x * x;
    double term = 1.0;  // q^k / k!
    double re = 0.0, im = 0.0;
    for (int k = 0; k < kMaxIterations; ++k) {
        const double t = term / (2 * k + 1);
        switch (k % 4) {
            case 0:
                re += t;
                break;
            case 1:
                im += t;
                break;
            case 2:
                re -= t;
                break;
            default:
                im -= t;
                break;
        }
        if (t < kEps * 0.25 * std::max(std::fabs(re), std::fabs(im))) break;
        term *= q / (k + 1);
    }
    return {x * re, x * im};
}

// G(x) from the continued fraction of erfc (Numerical Recipes 6.8, "frenel"), x >= kSeriesMax.
Complex aux_continued_fraction(double x) {
    const double pix2 = kPi * x * x;
    constexpr double kTiny = std::numeric_limits<double>::min() / kEps;
    Complex b(1.0, -pix2);
    Complex cc(1.0 / kTiny, 0.0);
    Complex d = 1.0 / b;
    Complex h = d;
    int n = -1;
    for (int k = 2; k < kMaxIterations; ++k) {
        n += 2;
        const double a = -static_cast<double>(n) * (n + 1);
        b += 4.0;
        d = 1.0 / (a * d + b);
        cc = b + a / cc;
        const Complex del = cc * d;
        h *= del;
        if (std::fabs(del.real() - 1.0) + std::fabs(del.imag()) < kEps) break;
    }
    h *= Complex(x, -x);
    return Complex(0.5, 0.5) * h;
}

// A&S 7.3.27-28 with two terms each.
Complex aux_asymptotic(double x) {
    const double u = 1.0 / (kPi * x * x);  // 1 / (pi x^2)
    const double u2 = u * u;
    const double f = (1.0 / (kPi * x)) * (1.0 - 3.0 * u2 + 105.0 * u2 * u2);
    const double g = (1.0 / (kPi * kPi * x * x * x)) * (1.0 - 15.0 * u2 + 945.0 * u2 * u2);
    return {g, f};
}

}  // namespace

Complex cis_pi(double y) {
    const double r = std::fmod(y, 2.0);  // exact
    return {std::cos(kPi * r), std::sin(kPi * r)};
}

Complex fresnel_aux(double x) {
    if (!(x >= 0.0)) {
        throw invalid_field("fresnel_aux argument", std::to_string(x), "must be >= 0");
    }
    if (x >= kAsymptoticMin) return aux_asymptotic(x);
    if (x >= kSeriesMax) return aux_continued_fraction(x);
    return (Complex(0.5, 0.5) - series(x)) * std::conj(cis_pi(0.5 * x * x));
}

Complex fresnel_cs(double x) {
    const double ax = std::fabs(x);
    Complex r;
    if (ax < kSeriesMax) {
        r = series(ax);
    } else if (std::isinf(ax)) {
        r = Complex(0.5, 0.5);
    } else {
        const Complex g = ax >= kAsymptoticMin ? aux_asymptotic(ax) : aux_continued_fraction(ax);
        r = Complex(0.5, 0.5) - g * cis_pi(0.5 * ax * ax);
    }
    return x < 0.0 ? -r : r;
}

}  // namespace pinmask
