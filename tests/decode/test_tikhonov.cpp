#include <doctest/doctest.h>

#include <Eigen/Dense>

#include "core/errors/error.hpp"
#include "decode/solvers/tikhonov.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Spectral filter against a dense Cholesky solve of (A^T A + lambda L^T L) x = A^T p; the
// systems used have condition numbers <= ~1e4 (|H| >= 1/3, lambda >= 1e-3).
constexpr double kTikhonovVsDenseTol = 1e-10;

}  // namespace

TEST_CASE("Tikhonov equals the dense normal-equation solve, identity and gradient") {
    struct Case {
        int R, C, pr, pc;
        double lambda;
    };
    const Case cases[] = {{8, 8, 3, 3, 1e-2},
                          {9, 7, 4, 4, 1e-3},
                          {13, 13, 5, 2, 0.3},
                          {16, 12, 6, 5, 1e-3},
                          {32, 32, 8, 8, 1e-2}};
    unsigned seed = 500;
    for (const Case& k : cases) {
        const Plane psf = random_psf(k.pr, k.pc, seed++);
        const Plane p = random_plane(k.R, k.C, seed++, -1.0, 1.0);
        const Eigen::MatrixXd A = dense_circulant(psf, k.R, k.C);
        const Eigen::MatrixXd Dr = dense_difference(k.R, k.C, true);
        const Eigen::MatrixXd Dc = dense_difference(k.R, k.C, false);
        for (auto reg : {TikhonovRegulariser::kIdentity, TikhonovRegulariser::kGradient}) {
            Eigen::MatrixXd M = A.transpose() * A;
            if (reg == TikhonovRegulariser::kIdentity) {
                M.diagonal().array() += k.lambda;
            } else {
                M += k.lambda * (Dr.transpose() * Dr + Dc.transpose() * Dc);
            }
            const Plane ref = as_plane(M.llt().solve(A.transpose() * as_vector(p)), k.R, k.C);
            const Plane x = make_tikhonov_filter(psf, k.R, k.C, k.lambda, reg).apply(p);
            INFO(k.R << " x " << k.C << " reg " << int(reg));
            CHECK(max_rel_error(x, ref) <= kTikhonovVsDenseTol);
        }
    }
}

TEST_CASE("Tikhonov penalty values and validation") {
    const Plane x = random_plane(5, 6, 7, -1.0, 1.0);
    CHECK_CLOSE(tikhonov_penalty(x, 2.0, TikhonovRegulariser::kIdentity), 2.0 * x.square().sum(),
                1e-15);
    CHECK(tikhonov_penalty(Plane::Constant(5, 6, 4.0), 2.0, TikhonovRegulariser::kGradient) == 0.0);
    CHECK_THROWS_WITH_AS(
        make_tikhonov_filter(random_psf(3, 3, 1), 8, 8, -1.0, TikhonovRegulariser::kIdentity),
        doctest::Contains("lambda"), InvalidInput);
}

TEST_CASE("Tikhonov with lambda = 0 and a gradient regulariser is the pseudo-inverse") {
    // |H| >= 1/3 everywhere, so lambda = 0 gives the exact inverse: A x = p.
    const Plane psf = random_psf(3, 4, 9);
    const Plane p = random_plane(9, 10, 10, -1.0, 1.0);
    const Plane x = make_tikhonov_filter(psf, 9, 10, 0.0, TikhonovRegulariser::kGradient).apply(p);
    const Plane ax = as_plane(dense_circulant(psf, 9, 10) * as_vector(x), 9, 10);
    constexpr double kInverseTol = 1e-12;  // condition number <= 3 times rounding
    CHECK(max_rel_error(ax, p) <= kInverseTol);
}
