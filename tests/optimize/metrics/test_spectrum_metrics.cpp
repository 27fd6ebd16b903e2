#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_pattern.hpp"

using namespace pinmask;
using pinmask::test::random_pattern;

namespace {

// FFT against a direct O(n^4) DFT, and products/sums of O(n^2) such terms: round-off.
constexpr double kDirectTol = 1e-10;

// Direct DFT of the pattern at frequency (k, l): sum_j exp(-2 pi i (k r_j + l c_j) / n).
std::complex<double> direct_dft(const Pattern& p, int k, int l) {
    std::complex<double> s = 0;
    for (const Cell& c : p.pinholes)
        s += std::polar(1.0, -2 * std::numbers::pi * ((k * c.row + l * c.col) % p.n) / p.n);
    return s;
}

// An m x m kernel (m = n * ppc) holding a ppc x ppc blur with unequal weights at the origin.
Plane test_kernel(int m, int ppc) {
    Plane k = Plane::Zero(m, m);
    for (int r = 0; r < ppc; ++r)
        for (int c = 0; c < ppc; ++c) k(r, c) = 1.0 + 0.3 * r + 0.1 * c * c;
    return k / k.sum();
}

}  // namespace

TEST_CASE("a single pinhole has a flat spectrum: flatness 1, min |P^| = 1") {
    for (int n : {2, 5, 16}) {
        Pattern p;
        p.n = n;
        p.pinholes = {{n / 2, 1}};
        const PatternSpectrumMetrics m = pattern_spectrum_metrics(pattern_spectrum(p));
        CHECK(m.spectral_flatness == doctest::Approx(1.0).epsilon(kDirectTol));
        CHECK(m.min_abs_pattern_spectrum == doctest::Approx(1.0).epsilon(kDirectTol));
        CHECK(m.light_gain == 1.0);
        CHECK(m.open_fraction == doctest::Approx(1.0 / (n * n)));
    }
}

TEST_CASE("metrics match direct DFT sums (odd, prime, 2^k sizes)") {
    for (int n : {7, 13, 16}) {
        const Pattern p = random_pattern(n, n + 2, 7u * n);
        double min_abs = 1e300, sum = 0, sum_log = 0;
        for (int k = 0; k < n; ++k)
            for (int l = 0; l < n; ++l) {
                if (k == 0 && l == 0) continue;
                const double a = std::abs(direct_dft(p, k, l));
                min_abs = std::min(min_abs, a);
                sum += a * a;
                sum_log += std::log(a * a);
            }
        const double cnt = n * n - 1.0;
        if (min_abs <= kSpectralZeroTol * (n + 2)) {  // an exact zero: flatness 0 by definition
            min_abs = 0.0;
            sum_log = -std::numeric_limits<double>::infinity();
        }
        const PatternSpectrumMetrics m = pattern_spectrum_metrics(pattern_spectrum(p));
        INFO("n " << n);
        CHECK(std::fabs(m.min_abs_pattern_spectrum - min_abs) <= kDirectTol);
        CHECK(std::fabs(m.spectral_flatness - std::exp(sum_log / cnt) / (sum / cnt)) <= kDirectTol);
        CHECK(m.spectral_flatness < 1.0);
        CHECK(m.light_gain == n + 2);
    }
}

TEST_CASE("a spectral zero gives flatness 0 and min |P^| 0") {
    Pattern p;
    p.n = 2;
    p.pinholes = {{0, 0}, {0, 1}};  // P^(0, 1) = 1 + e^{-i pi} = 0
    const PatternSpectrumMetrics m = pattern_spectrum_metrics(pattern_spectrum(p));
    CHECK(m.min_abs_pattern_spectrum <= kDirectTol);
    CHECK(m.spectral_flatness <= kDirectTol);
}

TEST_CASE("OTF condition number: factorised form equals the FFT of the full PSF") {
    for (const auto& size : {std::pair{4, 4}, std::pair{5, 3}, std::pair{7, 2}}) {
        const int n = size.first, ppc = size.second;
        const int m = n * ppc;
        const Pattern p = random_pattern(n, n, 31u * n);
        const Plane kernel = test_kernel(m, ppc);
        // Full PSF on the m x m torus: the kernel placed at every pinhole's cell.
        Plane psf = Plane::Zero(m, m);
        for (const Cell& c : p.pinholes) psf += circshift(kernel, c.row * ppc, c.col * ppc);
        const ComplexPlane kernel_otf = expand_half_spectrum(Fft2(m, m).forward(kernel), m);
        const ComplexPlane psf_otf = expand_half_spectrum(Fft2(m, m).forward(psf), m);
        const double thr = kPassbandFraction * kernel_otf.abs().maxCoeff();
        double lo = 1e300, hi = 0;
        long long count = 0;
        for (int k = 0; k < m; ++k)
            for (int l = 0; l < m; ++l) {
                if (std::abs(kernel_otf(k, l)) < thr) continue;
                lo = std::min(lo, std::abs(psf_otf(k, l)));
                hi = std::max(hi, std::abs(psf_otf(k, l)));
                ++count;
            }
        const OtfCondition c = otf_condition(pattern_spectrum(p), kernel_otf);
        INFO("n " << n << " ppc " << ppc);
        CHECK(c.passband_frequencies == count);
        CHECK_CLOSE(c.max_abs_otf, hi, kDirectTol);
        if (lo <= kSpectralZeroTol * hi) {  // a zero of the pattern spectrum in the passband
            CHECK(c.min_abs_otf == 0.0);
            CHECK(std::isinf(c.condition_number));
        } else {
            CHECK_CLOSE(c.min_abs_otf, lo, kDirectTol);
            CHECK_CLOSE(c.condition_number, hi / lo, kDirectTol);
        }
    }
    // A single pinhole: the condition is the kernel's own over its passband.
    Pattern one;
    one.n = 4;
    one.pinholes = {{0, 0}};
    const ComplexPlane kernel_otf =
        expand_half_spectrum(Fft2(16, 16).forward(test_kernel(16, 4)), 16);
    const OtfCondition c = otf_condition(pattern_spectrum(one), kernel_otf, 1.0);
    CHECK(c.passband_frequencies >= 1);
    CHECK_CLOSE(c.condition_number, 1.0, kDirectTol);  // fraction 1: only the peak(s) remain
    CHECK_THROWS_AS(otf_condition(pattern_spectrum(one), kernel_otf.topLeftCorner(6, 6)),
                    InvalidInput);
}
