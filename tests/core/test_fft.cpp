#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::random_plane;

namespace {

// Round-off of an O(N log N) FFT against an O(N^2) sum in double: a few ulps times log N.
constexpr double kFftVsDirectTol = 1e-11;

// Direct separable DFT (rows then columns), O(R C (R + C)), sign -1, unnormalised.
ComplexPlane direct_dft(const ComplexPlane& x, int sign) {
    const Eigen::Index R = x.rows(), C = x.cols();
    ComplexPlane t(R, C), y(R, C);
    for (Eigen::Index r = 0; r < R; ++r)
        for (Eigen::Index l = 0; l < C; ++l) {
            std::complex<double> s = 0;
            for (Eigen::Index c = 0; c < C; ++c)
                s += x(r, c) *
                     std::polar(1.0, sign * 2 * std::numbers::pi * double((l * c) % C) / C);
            t(r, l) = s;
        }
    for (Eigen::Index l = 0; l < C; ++l)
        for (Eigen::Index k = 0; k < R; ++k) {
            std::complex<double> s = 0;
            for (Eigen::Index r = 0; r < R; ++r)
                s += t(r, l) *
                     std::polar(1.0, sign * 2 * std::numbers::pi * double((k * r) % R) / R);
            y(k, l) = s;
        }
    return y;
}

double max_abs(const ComplexPlane& a) { return a.abs().maxCoeff(); }

void check_real_pair(int rows, int cols) {
    const Plane x = random_plane(rows, cols, 1000u * rows + cols, -1.0, 1.0);
    const Fft2 fft(rows, cols);
    const ComplexPlane half = fft.forward(x);
    const ComplexPlane ref = direct_dft(x.cast<std::complex<double>>(), -1);
    const ComplexPlane full = expand_half_spectrum(half, cols);
    INFO("size " << rows << " x " << cols);
    CHECK(max_abs(full - ref) <= kFftVsDirectTol * std::max(1.0, max_abs(ref)));
    const Plane back = fft.inverse(half);
    CHECK((back - x).abs().maxCoeff() <= kFftVsDirectTol);
}

}  // namespace

TEST_CASE("r2c/c2r match the direct DFT for every size 1..64") {
    for (int n = 1; n <= 64; ++n) {
        check_real_pair(n, n);
        check_real_pair(n, (n * 7) % 13 + 1);  // non-square, odd and even mixes
    }
}

TEST_CASE("large primes") {
    check_real_pair(1, 1009);
    check_real_pair(257, 3);
    check_real_pair(131, 127);
}

TEST_CASE("complex transform matches the direct DFT and round-trips") {
    for (int n : {1, 2, 3, 5, 8, 16, 17, 31}) {
        const Plane re = random_plane(n, n + 1, 7u * n, -1.0, 1.0),
                    im = random_plane(n, n + 1, 9u * n, -1.0, 1.0);
        ComplexPlane x(n, n + 1);
        x.real() = re;
        x.imag() = im;
        const FftC2 fft(n, n + 1);
        const ComplexPlane X = fft.forward(x);
        CHECK(max_abs(X - direct_dft(x, -1)) <= kFftVsDirectTol * max_abs(X));
        CHECK(max_abs(fft.inverse(X) - x) <= kFftVsDirectTol);
    }
}

TEST_CASE("plans are created safely from many threads and give identical results") {
    const Plane x = random_plane(48, 40, 3, -1.0, 1.0);
    const ComplexPlane ref = Fft2(48, 40).forward(x);
    std::vector<std::thread> threads;
    std::vector<double> err(8, 1.0);
    for (int t = 0; t < 8; ++t) {
        threads.emplace_back([&, t] {
            const Fft2 fft(48 + (t % 2), 40);  // also creates new plans concurrently
            const Fft2 same(48, 40);
            err[t] = max_abs(same.forward(x) - ref);
            (void)fft;
        });
    }
    for (auto& th : threads) th.join();
    for (double e : err) CHECK(e == 0.0);
}

TEST_CASE("size errors are InvalidInput") {
    CHECK_THROWS_AS(Fft2(0, 4), InvalidInput);
    const Fft2 fft(4, 4);
    CHECK_THROWS_AS(fft.forward(Plane::Zero(4, 5)), InvalidInput);
}
