#include <doctest/doctest.h>

#include <array>
#include <complex>
#include <numbers>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/psf2otf.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// FFT against an O(N^2) DFT sum in double: a few ulps times log N of the largest coefficient.
constexpr double kOtfVsDirectTol = 1e-12;

// Explicit deconvwnr centring: pad at the top-left, then shift by -floor(size / 2) per axis.
Plane shifted_by_hand(const Plane& psf, int R, int C) {
    Plane padded = Plane::Zero(R, C);
    padded.topLeftCorner(psf.rows(), psf.cols()) = psf;
    return circshift(padded, -static_cast<int>(psf.rows() / 2), -static_cast<int>(psf.cols() / 2));
}

// Direct DFT of a real plane, columns 0 .. C/2 only.
ComplexPlane direct_half_dft(const Plane& x) {
    const Eigen::Index R = x.rows(), C = x.cols();
    ComplexPlane out(R, C / 2 + 1);
    for (Eigen::Index k = 0; k < R; ++k)
        for (Eigen::Index l = 0; l <= C / 2; ++l) {
            std::complex<double> s = 0;
            for (Eigen::Index r = 0; r < R; ++r)
                for (Eigen::Index c = 0; c < C; ++c)
                    s += x(r, c) *
                         std::polar(1.0, -2 * std::numbers::pi *
                                             (double((k * r) % R) / R + double((l * c) % C) / C));
            out(k, l) = s;
        }
    return out;
}

}  // namespace

TEST_CASE("psf_to_origin puts the central element (floor(size/2)) at the origin") {
    for (const auto& psf_size : {std::pair{1, 1}, {2, 2}, {3, 3}, {4, 5}, {5, 4}, {7, 2}}) {
        const int pr = psf_size.first, pc = psf_size.second;
        Plane psf = Plane::Zero(pr, pc);
        psf(pr / 2, pc / 2) = 7.0;
        const Plane out = psf_to_origin(psf, 9, 8);
        INFO("psf " << pr << " x " << pc);
        CHECK(out(0, 0) == 7.0);
        CHECK(out.sum() == 7.0);
    }
    // The top-left element lands at (-floor(pr/2), -floor(pc/2)) mod size.
    Plane psf = Plane::Zero(4, 3);
    psf(0, 0) = 1.0;
    CHECK(psf_to_origin(psf, 9, 8)(9 - 2, 8 - 1) == 1.0);
}

TEST_CASE("psf_to_origin equals the element-by-element modular shift (block copies)") {
    // The reference: psf(r, c) -> ((r - floor(pr/2)) mod rows, (c - floor(pc/2)) mod cols), one
    // value at a time, for PSFs from 1 x 1 to the working size itself, odd and even.
    for (const std::array<int, 4>& k :
         {std::array{1, 1, 5, 4}, std::array{3, 2, 5, 4}, std::array{5, 4, 5, 4},
          std::array{4, 5, 9, 8}, std::array{9, 8, 9, 8}, std::array{2, 7, 3, 8}}) {
        const int pr = k[0], pc = k[1], rows = k[2], cols = k[3];
        Plane psf(pr, pc);
        for (Eigen::Index i = 0; i < psf.size(); ++i) psf.data()[i] = 1.0 + double(i);
        Plane ref = Plane::Zero(rows, cols);
        for (int r = 0; r < pr; ++r)
            for (int c = 0; c < pc; ++c)
                ref((r - pr / 2 + rows) % rows, (c - pc / 2 + cols) % cols) = psf(r, c);
        INFO(pr << " x " << pc << " into " << rows << " x " << cols);
        CHECK((psf_to_origin(psf, rows, cols) == ref).all());
    }
}

TEST_CASE("psf2otf equals the direct DFT of the explicitly shifted PSF, odd and even sizes") {
    const std::pair<int, int> grids[] = {{8, 8}, {9, 7}, {13, 13}, {16, 12}, {1, 5}};
    const std::pair<int, int> psfs[] = {{1, 1}, {3, 3}, {4, 4}, {5, 2}, {2, 3}, {8, 7}};
    unsigned seed = 1;
    for (const auto& grid : grids)
        for (const auto& psf_size : psfs) {
            const int R = grid.first, C = grid.second, pr = psf_size.first, pc = psf_size.second;
            if (pr > R || pc > C) continue;
            const Plane psf = random_plane(pr, pc, seed++, -1.0, 1.0);
            const ComplexPlane otf = psf2otf(psf, R, C);
            const ComplexPlane ref = direct_half_dft(shifted_by_hand(psf, R, C));
            INFO("grid " << R << " x " << C << ", psf " << pr << " x " << pc);
            REQUIRE(otf.rows() == R);
            REQUIRE(otf.cols() == C / 2 + 1);
            CHECK((otf - ref).abs().maxCoeff() <=
                  kOtfVsDirectTol * std::max(1.0, ref.abs().maxCoeff()));
        }
}

TEST_CASE("psf2otf refuses a PSF larger than the grid and an empty PSF") {
    CHECK_THROWS_AS(psf2otf(Plane::Ones(5, 3), 4, 8), InvalidInput);
    CHECK_THROWS_AS(psf2otf(Plane::Ones(3, 9), 4, 8), InvalidInput);
    CHECK_THROWS_AS(psf2otf(Plane(0, 0), 4, 8), InvalidInput);
}
