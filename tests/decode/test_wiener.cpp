#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/psf2otf.hpp"
#include "decode/solvers/wiener.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Spectral solve against a dense Cholesky solve of (A^T A + NSR I) x = A^T p: the condition
// number is at most (1 + NSR) / NSR ~ 1e3 for the NSR used, times double rounding ~1e-16, with
// room for N-term sums.
constexpr double kWienerVsDenseTol = 1e-10;
// Two evaluations of the same spectral formula along different FFT paths (half vs full
// spectrum): a few ulps of the largest coefficient.
constexpr double kSpectralPathTol = 1e-12;

Eigen::VectorXd dense_wiener(const Plane& psf, const Plane& p, double nsr) {
    const int R = static_cast<int>(p.rows()), C = static_cast<int>(p.cols());
    const Eigen::MatrixXd A = dense_circulant(psf, R, C);
    Eigen::MatrixXd M = A.transpose() * A;
    M.diagonal().array() += nsr;
    return M.llt().solve(A.transpose() * as_vector(p));
}

}  // namespace

TEST_CASE("Wiener equals the dense circulant solve (odd, even, prime sizes)") {
    struct Case {
        int R, C, pr, pc;
        double nsr;
    };
    const Case cases[] = {{8, 8, 3, 3, 1e-2},   {9, 7, 4, 4, 1e-3},    {13, 13, 5, 2, 1e-2},
                          {16, 12, 6, 5, 1e-3}, {32, 32, 8, 8, 1e-2},  {7, 9, 7, 9, 1e-2},
                          {13, 13, 1, 1, 1e-3}, {32, 32, 11, 16, 1e-3}};
    unsigned seed = 10;
    for (const Case& k : cases) {
        const Plane psf = random_psf(k.pr, k.pc, seed++);
        const Plane p = random_plane(k.R, k.C, seed++, -1.0, 1.0);
        const WienerFilter w(psf, k.R, k.C, k.nsr);
        const Plane x = w.apply(p);
        const Plane ref = as_plane(dense_wiener(psf, p, k.nsr), k.R, k.C);
        INFO("grid " << k.R << " x " << k.C << ", psf " << k.pr << " x " << k.pc);
        CHECK(max_rel_error(x, ref) <= kWienerVsDenseTol);
    }
}

TEST_CASE("Wiener with tiny NSR on a well-conditioned PSF is the inverse filter") {
    // |H| >= 1/3 for random_psf, so 1e-12 is far above the deconvwnr floor's reach.
    const Plane psf = random_psf(5, 4, 3);
    const Plane x_true = random_plane(13, 11, 4, -1.0, 1.0);
    const Eigen::MatrixXd A = dense_circulant(psf, 13, 11);
    const Plane p = as_plane(A * as_vector(x_true), 13, 11);
    const Plane x = WienerFilter(psf, 13, 11, 1e-12).apply(p);
    constexpr double kInverseTol = 1e-10;  // NSR / |H|^2 <= 1e-11 bias plus rounding
    CHECK(max_rel_error(x, x_true) <= kInverseTol);
}

TEST_CASE("per-frequency NSR: constant array equals scalar; asymmetric array takes real part") {
    const int R = 9, C = 8;
    const Plane psf = random_psf(3, 4, 21);
    const Plane p = random_plane(R, C, 22, -1.0, 1.0);
    const Plane x_scalar = WienerFilter(psf, R, C, 0.05).apply(p);
    const Plane x_array = WienerFilter(psf, R, C, Plane::Constant(R, C, 0.05)).apply(p);
    CHECK(max_rel_error(x_array, x_scalar) <= kSpectralPathTol);

    // Asymmetric NSR: reference real(ifft2(G .* fft2(p))) on the full complex spectrum.
    const Plane nsr = random_plane(R, C, 23, 0.0, 2.0);
    const Plane x = WienerFilter(psf, R, C, nsr).apply(p);
    const ComplexPlane h = expand_half_spectrum(psf2otf(psf, R, C), C);
    ComplexPlane g(R, C);
    for (Eigen::Index i = 0; i < g.size(); ++i) {
        g.data()[i] = std::conj(h.data()[i]) /
                      std::max(std::norm(h.data()[i]) + nsr.data()[i], kDeconvwnrDenominatorFloor);
    }
    const FftC2 fft(R, C);
    const ComplexPlane full = fft.inverse(g * fft.forward(p.cast<std::complex<double>>()));
    const Plane ref = full.real();
    CHECK(max_rel_error(x, ref) <= kSpectralPathTol);
}

TEST_CASE("deconvwnr floor: |H|^2 + NSR below sqrt(eps) is divided by the floor, H = 0 gives 0") {
    // PSF [1, t] / (1 + t) on a 1 x 2 grid: H(0) = 1, H(1/2) = (1 - t) / (1 + t).
    const double t = 1.0 - 2e-5;  // |H(1/2)|^2 ~ 1e-10 < floor
    Plane psf(1, 2);
    psf << 1.0, t;
    psf /= psf.sum();
    const WienerFilter w(psf, 1, 2, 0.0);
    const double h1 = (psf(0, 1) - psf(0, 0));  // centre element index 1 sits at the origin
    CHECK_CLOSE(w.half_spectrum()(0, 1).real(), h1 / kDeconvwnrDenominatorFloor, 1e-12);
    CHECK_CLOSE(w.half_spectrum()(0, 0).real(), 1.0, 1e-15);

    Plane flat(1, 2);
    flat << 0.5, 0.5;
    const WienerFilter w0(flat, 1, 2, 0.0, 0.0);  // no floor: H(1/2) = 0 exactly
    CHECK(w0.half_spectrum()(0, 1) == std::complex<double>(0.0, 0.0));
    CHECK(is_all_finite(w0.apply(Plane::Ones(1, 2))));
}

TEST_CASE("WienerFilter validates its inputs, naming the field") {
    const Plane psf = random_psf(3, 3, 5);
    CHECK_THROWS_WITH_AS(WienerFilter(psf, 8, 8, -1.0), doctest::Contains("nsr"), InvalidInput);
    CHECK_THROWS_WITH_AS(WienerFilter(psf, 8, 8, std::nan("")), doctest::Contains("nsr"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(WienerFilter(psf, 8, 8, Plane::Constant(8, 8, -0.1)),
                         doctest::Contains("nsr_per_frequency"), InvalidInput);
    CHECK_THROWS_WITH_AS(WienerFilter(psf, 8, 8, Plane::Constant(8, 7, 0.1)),
                         doctest::Contains("nsr_per_frequency"), InvalidInput);
    CHECK_THROWS_AS(WienerFilter(psf, 2, 8, 0.1), InvalidInput);
    const WienerFilter w(psf, 8, 8, 0.1);
    CHECK_THROWS_WITH_AS(w.apply(Plane::Zero(8, 9)), doctest::Contains("capture"), InvalidInput);
}

TEST_CASE("float-rounded capture decodes within gain * float epsilon * ||p|| of double") {
    const int R = 32, C = 24;
    const Plane psf = random_psf(8, 8, 31);
    const Plane p = random_plane(R, C, 32, 0.0, 1.0);
    const Plane p_float = p.cast<float>().cast<double>();
    for (double nsr : {1e-4, 1e-2, 1.0}) {
        const WienerFilter w(psf, R, C, nsr);
        const double dx = std::sqrt((w.apply(p_float) - w.apply(p)).square().sum());
        // Rounding to float moves each pixel by at most u |p_i| (u = 2^-24), so the capture by
        // at most u ||p||_2; the filter's l2 gain bounds how far x moves (Parseval). Slack 1.01
        // covers the double-precision rounding of the two evaluations.
        constexpr double kFloatUnitRoundoff = 5.9604644775390625e-08;
        const double bound = 1.01 * w.gain() * kFloatUnitRoundoff * std::sqrt(p.square().sum());
        INFO("nsr " << nsr << ", |dx| " << dx << ", bound " << bound);
        CHECK(dx <= bound);
        CHECK(dx > 0.0);  // the capture did change
    }
}
