#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/fft/fft.hpp"
#include "decode/solvers/gradient.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Sums of N products of O(1) values along two different evaluation orders.
constexpr double kAdjointTol = 1e-13;
// Closed-form eigenvalues against the FFT of the dense operator's first column.
constexpr double kSymbolTol = 1e-12;

}  // namespace

TEST_CASE("gradient equals the dense periodic difference matrices; div = -grad^T") {
    for (const auto& size : {std::pair{1, 5}, {4, 4}, {7, 5}, {8, 13}}) {
        const int R = size.first, C = size.second;
        const Plane x = random_plane(R, C, 100 + R, -1.0, 1.0);
        Plane d_r, d_c;
        gradient(x, d_r, d_c);
        const Eigen::MatrixXd Dr = dense_difference(R, C, true);
        const Eigen::MatrixXd Dc = dense_difference(R, C, false);
        INFO(R << " x " << C);
        // Each entry is one subtraction of the same two doubles: bit-identical.
        CHECK((as_vector(d_r) - Dr * as_vector(x)).cwiseAbs().maxCoeff() == 0.0);
        CHECK((as_vector(d_c) - Dc * as_vector(x)).cwiseAbs().maxCoeff() == 0.0);
        const Plane a = random_plane(R, C, 200 + R, -1.0, 1.0),
                    b = random_plane(R, C, 300 + R, -1.0, 1.0);
        const Eigen::VectorXd ref =
            -(Dr.transpose() * as_vector(a) + Dc.transpose() * as_vector(b));
        CHECK((as_vector(divergence(a, b)) - ref).cwiseAbs().maxCoeff() <= kAdjointTol);
        CHECK_CLOSE((d_r * a + d_c * b).sum(), -(x * divergence(a, b)).sum(), kAdjointTol);
    }
}

TEST_CASE("total variation: isotropic sum, known values") {
    // A single bright pixel on a 5 x 5 torus: differences 1 at (2,2) in both directions
    // (sqrt 2), and -1 at the row above / column to the left (1 each).
    Plane x = Plane::Zero(5, 5);
    x(2, 2) = 1.0;
    CHECK(total_variation(x) == doctest::Approx(std::sqrt(2.0) + 2.0).epsilon(1e-15));
    CHECK(total_variation(Plane::Constant(4, 6, 3.0)) == 0.0);
    // A vertical step of height h across a C-wide torus of R rows: two edges, C each.
    Plane s = Plane::Zero(6, 7);
    s.topRows(3).setConstant(2.5);
    CHECK(total_variation(s) == doctest::Approx(2 * 7 * 2.5).epsilon(1e-15));
}

TEST_CASE("gradient_gram_symbol is the spectrum of grad^T grad") {
    for (const auto& size : {std::pair{4, 4}, {7, 5}, {8, 13}}) {
        const int R = size.first, C = size.second;
        const Eigen::MatrixXd Dr = dense_difference(R, C, true);
        const Eigen::MatrixXd Dc = dense_difference(R, C, false);
        const Eigen::MatrixXd L = Dr.transpose() * Dr + Dc.transpose() * Dc;
        // L is circulant: its eigenvalues are the DFT of its first column.
        const Plane col0 = as_plane(L.col(0), R, C);
        const ComplexPlane ref = Fft2(R, C).forward(col0);
        const Plane s = gradient_gram_symbol(R, C);
        INFO(R << " x " << C);
        CHECK((s - ref.real()).abs().maxCoeff() <= kSymbolTol);
        CHECK(ref.imag().abs().maxCoeff() <= kSymbolTol);
        CHECK(s.maxCoeff() <= 8.0);
    }
}
