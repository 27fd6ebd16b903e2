#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/psf/psf.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_pattern.hpp"

using namespace pinmask;
using pinmask::test::random_pattern;

namespace {

// sum of N^2 values each <= 1, normalised by K.
constexpr double kSumTol = 1e-13;
// FFT round-off against the factorised product, relative to the largest coefficient (the DC
// term, 1): a few ulps times log N.
constexpr double kOtfTol = 1e-12;

Kernel fresnel_kernel(int ppc, int max_width) {
    KernelSpec s;
    s.model = "fresnel";
    return make_kernel(paper_camera(), s, ppc, KernelOptions{0.999, max_width});
}

}  // namespace

TEST_CASE("factorised OTF equals the FFT of the synthesised PSF (odd, even, prime n and ppc)") {
    for (int n : {1, 2, 5, 7, 16}) {
        for (int ppc : {1, 3, 8}) {
            const Pattern p = random_pattern(n, std::max(1, n * n / 4), 17u * n + ppc);
            // Kernels wider than the torus exercise the fold as well.
            const Kernel k = fresnel_kernel(ppc, 3 * n * ppc);
            // The direct sum, so the comparison with the factorisation is not circular.
            const Plane psf = synthesize_psf(p, k, ppc, PsfMethod::kDirect);
            INFO("n = " << n << " ppc = " << ppc);
            REQUIRE(psf.rows() == n * ppc);
            CHECK(std::fabs(psf.sum() - 1) <= kSumTol);
            const ComplexPlane ref = Fft2(n * ppc, n * ppc).forward(psf);
            const ComplexPlane otf = psf_otf(p, k, ppc);
            CHECK((otf - ref).abs().maxCoeff() <= kOtfTol * ref.abs().maxCoeff());
        }
    }
}

TEST_CASE("the Fourier path equals the direct sum; auto takes it for many wide kernels") {
    for (int n : {3, 8, 11}) {
        const Pattern p = random_pattern(n, n * n / 2 + 1, 5u * n);
        const Kernel k = fresnel_kernel(4, 2 * n * 4);
        const Plane direct = synthesize_psf(p, k, 4, PsfMethod::kDirect);
        const Plane fourier = synthesize_psf(p, k, 4, PsfMethod::kFourier);
        INFO("n = " << n);
        CHECK((direct - fourier).abs().maxCoeff() <= kOtfTol * direct.maxCoeff());
        CHECK((fourier >= 0).all());
        CHECK((synthesize_psf(p, k, 4) - direct).abs().maxCoeff() <= kOtfTol * direct.maxCoeff());
    }
}

TEST_CASE("placement: a kernel filling its cell reproduces the upsampled pattern") {
    const int ppc = 4;
    const Pattern p = random_pattern(7, 9, 3);
    const Kernel fill = measured_kernel(Plane::Ones(ppc, ppc), ppc, "cell");
    CHECK(fill.origin_row == 0);
    const Plane psf = synthesize_psf(p, fill, ppc);
    const auto occ = occupancy(p);
    for (int r = 0; r < 7 * ppc; ++r) {
        for (int c = 0; c < 7 * ppc; ++c) {
            const double expect = occ[(r / ppc) * 7 + c / ppc] ? 1.0 / (9 * ppc * ppc) : 0.0;
            CHECK(psf(r, c) == doctest::Approx(expect).epsilon(1e-15));
        }
    }
}

TEST_CASE("wrap-around: shifted copies of the kernel on the torus, folding wide kernels") {
    // Reference: the PSF as a sum of circularly shifted single-pinhole PSFs (core circshift).
    const int n = 5, ppc = 3;
    Pattern p;
    p.n = n;
    p.min_spacing_cells = 0;
    p.pinholes = {{0, 0}, {4, 4}, {2, 0}, {0, 3}};
    const Kernel k = fresnel_kernel(ppc, 11);
    const Plane k0 = kernel_on_torus(k, n, ppc);
    CHECK(std::fabs(k0.sum() - 1) <= kSumTol);
    Plane ref = Plane::Zero(n * ppc, n * ppc);
    for (const Cell& c : p.pinholes) ref += circshift(k0, c.row * ppc, c.col * ppc) / 4.0;
    CHECK((synthesize_psf(p, k, ppc) - ref).abs().maxCoeff() <= 1e-16);
    // Corner pinhole: its light reaches row 0 and column 0 through the seam.
    Pattern corner = p;
    corner.pinholes = {{4, 4}};
    const Plane psf = synthesize_psf(corner, k, ppc);
    CHECK(psf(0, 0) > 0);
    // A 10 x 10 ones kernel on a 4 x 4 torus folds to counts 3, 3, 2, 2 per axis.
    const Kernel ones = measured_kernel(Plane::Ones(10, 10), 4, "ones");
    const Plane folded = kernel_on_torus(ones, 1, 4);
    CHECK(std::fabs(folded.sum() - 1) <= kSumTol);
    CHECK(folded.maxCoeff() == doctest::Approx(9.0 / 100));
    CHECK(folded.minCoeff() == doctest::Approx(4.0 / 100));
}

TEST_CASE("1 x 1 grid: the PSF is the folded kernel") {
    Pattern p;
    p.n = 1;
    p.tiles_rows = p.tiles_cols = 1;
    p.min_spacing_cells = 0;
    p.pinholes = {{0, 0}};
    const Kernel k = fresnel_kernel(8, 41);
    const Plane psf = synthesize_psf(p, k, 8);
    CHECK(psf.rows() == 8);
    CHECK((psf - kernel_on_torus(k, 1, 8)).abs().maxCoeff() == 0.0);
    const ComplexPlane otf = psf_otf(p, k, 8);
    CHECK((otf - Fft2(8, 8).forward(psf)).abs().maxCoeff() <= kOtfTol);
}

TEST_CASE("pattern spectrum is the n x n DFT of the occupancy") {
    const Pattern p = random_pattern(6, 10, 9);
    const ComplexPlane s = pattern_spectrum(p);
    CHECK(s(0, 0).real() == doctest::Approx(10.0));
    std::complex<double> direct = 0;
    for (const Cell& h : p.pinholes)
        direct += std::polar(1.0, -2 * M_PI * (2 * h.row + 5 * h.col) / 6.0);
    CHECK(std::abs(s(2, 5) - direct) <= 1e-13);
}

TEST_CASE("the mask's PSF: paper-sized torus, kernel capped at the torus") {
    Mask m;
    m.pattern = random_pattern(16, 20, 1);
    m.camera = paper_camera();
    m.psf.pixels_per_cell = 8;
    const Kernel k = mask_kernel(m);
    CHECK(k.values.rows() <= 128);
    const Plane psf = mask_psf(m);
    CHECK(psf.rows() == 128);
    CHECK(std::fabs(psf.sum() - 1) <= kSumTol);
    CHECK((psf >= 0).all());
}

TEST_CASE("too large for memory is refused before allocating; bad sizes are InvalidInput") {
    ::setenv("PINMASK_MEMORY_LIMIT", "1G", 1);
    Pattern big;
    big.n = kMaxGrid;
    big.min_spacing_cells = 0;
    big.pinholes = {{0, 0}};
    const Kernel k = measured_kernel(Plane::Ones(1, 1), 8, "dot");
    CHECK_THROWS_AS(synthesize_psf(big, k, 8), ResourceLimit);
    CHECK_THROWS_AS(psf_otf(big, k, 8), ResourceLimit);
    CHECK_THROWS_AS(kernel_on_torus(k, kMaxGrid, 8), ResourceLimit);
    ::unsetenv("PINMASK_MEMORY_LIMIT");
    Pattern none;
    none.n = 4;
    CHECK_THROWS_AS(synthesize_psf(none, k, 8), InvalidInput);
    Pattern one;
    one.n = 4;
    one.pinholes = {{1, 1}};
    CHECK_THROWS_AS(synthesize_psf(one, k, 0), InvalidInput);
    one.pinholes = {{4, 1}};
    CHECK_THROWS_AS(synthesize_psf(one, k, 8), InvalidInput);
}
