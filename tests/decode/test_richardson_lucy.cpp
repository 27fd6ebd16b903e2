#include <doctest/doctest.h>

#include <cmath>

#include "core/errors/error.hpp"
#include "decode/solvers/richardson_lucy.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// One FFT-based RL step against the same step with dense matrices.
constexpr double kStepVsDenseTol = 1e-12;
// I-divergence may rise by rounding only: relative slack on a monotone sequence.
constexpr double kMonotoneSlack = 1e-12;

RichardsonLucyOptions iterations(int n) {
    RichardsonLucyOptions o;
    o.max_iterations = n;
    o.tolerance = 0.0;
    return o;
}

}  // namespace

TEST_CASE("one RL step equals x .* A^T(p ./ A x) ./ A^T 1 with dense matrices, both models") {
    for (ConvModel m : {ConvModel::kCyclic, ConvModel::kLinear}) {
        const ConvGeometry g = make_conv_geometry(m, 9, 8, 3, 4);
        const Plane psf = random_plane(3, 4, 30, 0.0, 1.0);
        const Plane p = random_plane(9, 8, 31, 0.5, 2.0);
        const Plane x0 = random_plane(g.work_rows, g.work_cols, 32, 0.5, 1.5);
        const Eigen::MatrixXd A = dense_model(psf, g);
        const Eigen::VectorXd ax = A * as_vector(x0);
        const Eigen::VectorXd at1 = A.transpose() * Eigen::VectorXd::Ones(A.rows());
        const Eigen::VectorXd back = A.transpose() * (as_vector(p).array() / ax.array()).matrix();
        Eigen::VectorXd ref(at1.size());
        for (Eigen::Index i = 0; i < ref.size(); ++i) {
            // Working-grid pixels no capture pixel sees are set to 0 (linear model).
            ref(i) = at1(i) > 1e-12 * at1.maxCoeff() ? as_vector(x0)(i) * back(i) / at1(i) : 0.0;
        }
        const ConvolutionOperator op(psf, g);
        const DecodeResult r = solve_richardson_lucy(op, psf, p, iterations(1), &x0);
        INFO("model " << int(m));
        CHECK(max_rel_error(r.image, as_plane(ref, g.work_rows, g.work_cols)) <= kStepVsDenseTol);
        // The residual and objective of that iterate, in the capture's units (the PSF's sum
        // is ~6 here: the solver's internal H / H(0) scaling must not leak into them).
        const Eigen::VectorXd ax1 = A * ref;
        const double res_ref = (ax1 - as_vector(p)).norm();
        CHECK(std::fabs(r.residual - res_ref) <= kStepVsDenseTol * res_ref);
        const double div_ref = i_divergence(p, as_plane(ax1, 9, 8));
        CHECK(std::fabs(r.objective - div_ref) <= kStepVsDenseTol * std::fabs(div_ref) + 1e-14);
        // The same step in float32: float rounding (6e-8) of values near 1 through one FFT
        // pair each way; 1e-5 is ~10x the measured gap on these 9 x 8 planes.
        RichardsonLucyOptions os = iterations(1);
        os.single_precision = true;
        const DecodeResult rs = solve_richardson_lucy(op, psf, p, os, &x0);
        CHECK(max_rel_error(rs.image, as_plane(ref, g.work_rows, g.work_cols)) <= 1e-5);
        CHECK(std::fabs(rs.residual - res_ref) <= 1e-5 * res_ref);
    }
}

TEST_CASE("RL does not increase the I-divergence (EM), cyclic and linear") {
    for (ConvModel m : {ConvModel::kCyclic, ConvModel::kLinear}) {
        const ConvGeometry g = make_conv_geometry(m, 16, 13, 5, 5);
        const Plane psf = random_plane(5, 5, 40, 0.0, 1.0) / 12.5;
        const ConvolutionOperator op(psf, g);
        Plane x = random_plane(g.work_rows, g.work_cols, 41, 0.0, 1.0);
        const Plane p = (op.apply(x) + 0.05 * random_plane(16, 13, 42, -1.0, 1.0)).max(0.0);
        const DecodeResult r = solve_richardson_lucy(op, psf, p, iterations(200));
        REQUIRE(r.history.size() == 200);
        for (std::size_t i = 1; i < r.history.size(); ++i) {
            INFO("model " << int(m) << " iteration " << i);
            CHECK(r.history[i].objective <= r.history[i - 1].objective * (1.0 + kMonotoneSlack));
        }
        CHECK(r.image.minCoeff() >= 0.0);
        CHECK(r.history.back().objective < 0.5 * r.history.front().objective);
    }
}

TEST_CASE("RL: the true scene is a fixed point of noise-free data; tolerance stops the run") {
    const Plane psf = random_psf(4, 4, 50);
    const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, 12, 12, 4, 4);
    const ConvolutionOperator op(psf, g);
    const Plane x = random_plane(12, 12, 51, 0.5, 1.5);
    const Plane p = op.apply(x);
    RichardsonLucyOptions o;
    o.max_iterations = 10;
    o.tolerance = 1e-12;
    const DecodeResult r = solve_richardson_lucy(op, psf, p, o, &x);
    constexpr double kFixedPointTol = 1e-13;  // ratio p / A x = 1 up to rounding
    CHECK(max_rel_error(r.image, x) <= kFixedPointTol);
    CHECK(r.converged);
    CHECK(r.iterations == 1);
}

TEST_CASE("RL guards: zero capture, negative capture values, negative PSF") {
    const Plane psf = random_psf(3, 3, 60);
    const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, 8, 8, 3, 3);
    const ConvolutionOperator op(psf, g);
    const DecodeResult zero = solve_richardson_lucy(op, psf, Plane::Zero(8, 8), iterations(20));
    CHECK((zero.image == 0.0).all());
    CHECK(std::isfinite(zero.objective));

    const Plane p = random_plane(8, 8, 61, -0.5, 1.0);  // negative values clipped to 0
    const DecodeResult r = solve_richardson_lucy(op, psf, p, iterations(50));
    CHECK(is_all_finite(r.image));
    CHECK(r.image.minCoeff() >= 0.0);

    Plane bad = psf;
    bad(0, 0) = -0.1;
    CHECK_THROWS_WITH_AS(solve_richardson_lucy(op, bad, p, iterations(5)), doctest::Contains("psf"),
                         InvalidInput);
    CHECK(i_divergence(Plane::Constant(2, 2, 3.0), Plane::Constant(2, 2, 3.0)) == 0.0);
    // sum(p log(p / q) - p + q) for p = 2, q = 1: 2 log 2 - 1.
    CHECK_CLOSE(i_divergence(Plane::Constant(1, 1, 2.0), Plane::Constant(1, 1, 1.0)),
                2.0 * std::log(2.0) - 1.0, 1e-15);
}
