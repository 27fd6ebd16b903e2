#include <doctest/doctest.h>

#include <cmath>

#include "core/error.hpp"
#include "decode/gradient.hpp"
#include "decode/tv_l2.hpp"
#include "decode/tvqc.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// TV at exit against the reference optimum: the bound.
constexpr double kTvObjectiveTol = 1e-4;
// ||A x - p|| <= eps (1 + this) at exit: the bound (kTvqcFeasibilityTol in tvqc.hpp).
constexpr double kConstraintTol = 1e-6;

struct Problem {
    Plane psf, p;
    ConvGeometry g;
};

Problem make_problem(ConvModel model, int R, int C, int pr, int pc, unsigned seed) {
    Problem P;
    P.g = make_conv_geometry(model, R, C, pr, pc);
    P.psf = random_plane(pr, pc, seed, 0.0, 1.0);
    P.psf /= P.psf.sum();
    Plane x = Plane::Zero(P.g.work_rows, P.g.work_cols);
    x.block(P.g.crop_row + R / 4, P.g.crop_col + C / 3, R / 2, C / 2) = 1.0;
    x.block(P.g.crop_row + 1, P.g.crop_col + 1, 3, 3) = 0.5;
    P.p = as_plane(dense_model(P.psf, P.g) * as_vector(x), R, C) +
          0.02 * random_plane(R, C, seed + 1);
    return P;
}

TvqcOptions tight(double eps) {
    TvqcOptions o;
    o.eps = eps;
    o.max_iterations = 50000;
    o.tolerance = 1e-8;  // ~1.3e4 iterations on 16 x 16, TV within ~1e-5 of the optimum
    o.record_history = false;
    return o;
}

}  // namespace

// By Lagrange duality the TV-L2 minimiser x* (lambda > 0) also solves TVQC with eps =
// ||A x* - p||, so the Newton reference of TV-L2 gives TVQC's optimal value TV(x*).
TEST_CASE("TVQC reaches the reference TV and holds the constraint (cyclic 16 x 16)") {
    const Problem P = make_problem(ConvModel::kCyclic, 16, 16, 5, 5, 11);
    const double lambda = 0.02;
    const Eigen::MatrixXd A = dense_model(P.psf, P.g);
    const Plane x_ref = as_plane(smoothed_tv_reference(A, as_vector(P.p), lambda, 16, 16), 16, 16);
    const ConvolutionOperator op(P.psf, P.g);
    const double eps = std::sqrt((op.apply(x_ref) - P.p).square().sum());
    const double tv_ref = total_variation(x_ref);
    const DecodeResult r = solve_tvqc(op, P.p, tight(eps));
    INFO("tv " << r.objective << " ref " << tv_ref << " residual " << r.residual << " eps " << eps
               << " after " << r.iterations);
    CHECK(r.converged);
    CHECK(r.objective <= tv_ref * (1.0 + kTvObjectiveTol));
    CHECK(r.objective >= tv_ref * (1.0 - kTvObjectiveTol));
    CHECK(r.residual <= eps * (1.0 + kConstraintTol));
    CHECK_CLOSE(r.residual, std::sqrt((op.apply(r.image) - P.p).square().sum()), 1e-12);
}

TEST_CASE("TVQC on the linear model agrees with TV-L2 through duality") {
    const Problem P = make_problem(ConvModel::kLinear, 9, 8, 4, 3, 12);
    const ConvolutionOperator op(P.psf, P.g);
    TvL2Options o;
    o.lambda = 0.02;
    o.max_iterations = 20000;
    o.tolerance = 1e-11;
    o.record_history = false;
    const DecodeResult tv = solve_tv_l2(op, P.p, o);
    const double eps = tv.residual;
    const DecodeResult r = solve_tvqc(op, P.p, tight(eps));
    const double tv_ref = total_variation(tv.image);
    INFO("tv " << r.objective << " ref " << tv_ref << " after " << r.iterations);
    CHECK(r.objective <= tv_ref * (1.0 + kTvObjectiveTol));
    CHECK(r.objective >= tv_ref * (1.0 - kTvObjectiveTol));
    CHECK(r.residual <= eps * (1.0 + kConstraintTol));
}

TEST_CASE("TVQC limits: eps >= ||p|| gives 0 at once; eps = 0 solves A x = p") {
    const Problem P = make_problem(ConvModel::kCyclic, 12, 12, 4, 4, 13);
    const ConvolutionOperator op(P.psf, P.g);
    const double p_norm = std::sqrt(P.p.square().sum());
    const DecodeResult zero = solve_tvqc(op, P.p, tight(p_norm * 1.0001));
    CHECK(zero.iterations == 0);
    CHECK((zero.image == 0.0).all());
    CHECK(zero.converged);

    // eps = 0 with a PSF whose OTF has no zeros: the feasible set is the single point H^-1 p.
    const Plane psf = random_psf(4, 4, 14);
    const ConvolutionOperator op2(psf, P.g);
    TvqcOptions o = tight(0.0);
    o.max_iterations = 200;
    const DecodeResult eq = solve_tvqc(op2, P.p, o);
    constexpr double kEqualityTol = 1e-12;  // one pseudo-inverse correction, |H| >= 1/3
    CHECK(eq.residual <= kEqualityTol * p_norm);
}

TEST_CASE("TVQC with a rank-deficient PSF (all pinholes on one row) and eps = 0") {
    // Row pattern [1 0 1 0]: H vanishes on the columns l = C/4 and 3C/4 of every row k.
    Plane psf = Plane::Zero(4, 4);
    psf(1, 0) = psf(1, 2) = 0.5;
    const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, 16, 16, 4, 4);
    const ConvolutionOperator op(psf, g);
    Plane x = Plane::Zero(16, 16);
    x.block(4, 4, 8, 6) = 1.0;
    const Plane p = op.apply(x);  // in the range of A
    TvqcOptions o = tight(0.0);
    o.max_iterations = 3000;
    const DecodeResult r = solve_tvqc(op, p, o);
    CHECK(is_all_finite(r.image));
    CHECK(r.residual <= kConstraintTol * std::sqrt(p.square().sum()));
    // TV of the exit point is no larger than that of the scene (which is feasible), up to the
    // unconverged part of the run.
    CHECK(r.objective <= total_variation(x) * (1.0 + 1e-2));
}

TEST_CASE("TVQC nonnegative, history and eps from the noise level") {
    const Problem P = make_problem(ConvModel::kCyclic, 16, 16, 5, 5, 15);
    const ConvolutionOperator op(P.psf, P.g);
    TvqcOptions o;
    o.eps = tvqc_eps_from_sigma(0.02, P.p.size());
    o.nonnegative = true;
    o.max_iterations = 2000;
    o.tolerance = 1e-6;
    const DecodeResult r = solve_tvqc(op, P.p, o);
    CHECK(r.image.minCoeff() >= 0.0);
    REQUIRE(r.history.size() == static_cast<std::size_t>(r.iterations));
    CHECK(r.history.back().residual <= 1.0 + 1e-3);  // relative to eps: feasible at the end
    for (const IterationRecord& rec : r.history) CHECK(std::isfinite(rec.objective));

    // eps = sigma sqrt(N) sqrt(1 + 2 sqrt(2 / N)).
    CHECK_CLOSE(tvqc_eps_from_sigma(0.1, 100), 0.1 * 10.0 * std::sqrt(1.0 + 2.0 * std::sqrt(0.02)),
                1e-15);
    CHECK(tvqc_eps_from_sigma(0.0, 100) == 0.0);
    CHECK_THROWS_WITH_AS(tvqc_eps_from_sigma(-1.0, 100), doctest::Contains("noise_sigma"),
                         InvalidInput);
    o.eps = -1.0;
    CHECK_THROWS_WITH_AS(solve_tvqc(op, P.p, o), doctest::Contains("eps"), InvalidInput);
}
