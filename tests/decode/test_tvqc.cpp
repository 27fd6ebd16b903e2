#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "decode/solvers/gradient.hpp"
#include "decode/solvers/tv_l2.hpp"
#include "decode/solvers/tvqc.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// TV at exit against the reference optimum: the required bound.
constexpr double kTvObjectiveTol = 1e-4;
// ||A x - p|| <= eps (1 + this) at exit: the required bound (kTvqcFeasibilityTol in tvqc.hpp).
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
          0.02 * random_plane(R, C, seed + 1, -1.0, 1.0);
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

namespace {

// The iteration of decode/solvers/tvqc.hpp written again from its formulas with dense matrices (no
// FFT, no fusion): K = (D, beta A, gamma I), M = D^T D + beta^2 Hc^T Hc + gamma^2 I with Hc the
// uncropped circulant (so M is the Fourier-diagonal preconditioner), the projections, the
// adaptive step balance with the primal residual ||K^T y|| and the dual residual of the
// previous step. Returns the records (TV(x_k), ||A x_k - p|| / eps) of iterations 1..K.
std::vector<std::pair<double, double>> dense_pdhg(const Problem& P, const Plane& x0, double eps,
                                                  bool nn, int iterations) {
    const int R = P.g.work_rows, C = P.g.work_cols;
    const Eigen::Index n = Eigen::Index(R) * C;
    const Eigen::MatrixXd A = dense_model(P.psf, P.g);
    const Eigen::MatrixXd Hc = dense_circulant(P.psf, R, C);
    const Eigen::MatrixXd Dr = dense_difference(R, C, true), Dc = dense_difference(R, C, false);
    const ConvolutionOperator op(P.psf, P.g);
    const double beta = std::sqrt(8.0) / std::sqrt(op.otf().abs2().mean());  // tvqc.hpp's choice
    const double gamma = nn ? 1.0 : 0.0;
    const Eigen::MatrixXd M = Dr.transpose() * Dr + Dc.transpose() * Dc +
                              beta * beta * Hc.transpose() * Hc +
                              gamma * gamma * Eigen::MatrixXd::Identity(n, n);
    const Eigen::LDLT<Eigen::MatrixXd> Mf(M);
    const Eigen::VectorXd p = as_vector(P.p);
    Eigen::VectorXd x = as_vector(x0), yr = Eigen::VectorXd::Zero(n), yc = yr, yw = yr;
    Eigen::VectorXd yq = Eigen::VectorXd::Zero(p.size());
    double tau = 0.99, sigma = 0.99, alpha = 0.5, dres_prev = -1.0;
    std::vector<std::pair<double, double>> out;
    for (int k = 1; k <= iterations; ++k) {
        const Eigen::VectorXd kty =
            Dr.transpose() * yr + Dc.transpose() * yc + beta * A.transpose() * yq + gamma * yw;
        if (alpha > 1e-3 && dres_prev >= 0.0) {
            const double pres = kty.norm();
            if (pres > 1.5 * dres_prev) {
                tau /= 1.0 - alpha;
                sigma *= 1.0 - alpha;
                alpha *= 0.95;
            } else if (pres < dres_prev / 1.5) {
                tau *= 1.0 - alpha;
                sigma /= 1.0 - alpha;
                alpha *= 0.95;
            }
        }
        const Eigen::VectorXd xn = x - tau * Mf.solve(kty);
        const Eigen::VectorXd xbar = 2.0 * xn - x, dx = x - xn;
        Eigen::VectorXd ar = yr + sigma * Dr * xbar, ac = yc + sigma * Dc * xbar;
        for (Eigen::Index i = 0; i < n; ++i) {
            const double s = std::max(1.0, std::hypot(ar(i), ac(i)));
            ar(i) /= s;
            ac(i) /= s;
        }
        const Eigen::VectorXd v = yq + sigma * beta * A * xbar;
        const double zn = (v / sigma - beta * p).norm();
        const double keep = zn > beta * eps ? 1.0 - beta * eps / zn : 0.0;
        const Eigen::VectorXd yqn = keep * (v - sigma * beta * p);
        const Eigen::VectorXd ywn = (yw + sigma * gamma * xbar).cwiseMin(0.0);
        double d2 = ((yr - ar) / sigma - Dr * dx).squaredNorm() +
                    ((yc - ac) / sigma - Dc * dx).squaredNorm() +
                    ((yq - yqn) / sigma - beta * A * dx).squaredNorm();
        if (nn) d2 += ((yw - ywn) / sigma - gamma * dx).squaredNorm();
        dres_prev = std::sqrt(d2);
        x = xn;
        yr = ar;
        yc = ac;
        yq = yqn;
        yw = ywn;
        const Eigen::VectorXd gr = Dr * x, gc = Dc * x;
        double tv = 0.0;
        for (Eigen::Index i = 0; i < n; ++i) tv += std::hypot(gr(i), gc(i));
        out.emplace_back(tv, (A * x - p).norm() / eps);
    }
    return out;
}

// Dense products and the FFT route round differently (~1e-15 relative per operation); over 40
// iterations of a contraction the records agree to ~1e-12. 1e-9 still catches any change of the
// iteration (a wrong sign, index or step is >= 1e-3).
constexpr double kDenseIterationTol = 1e-9;

}  // namespace

TEST_CASE("TVQC's fused iteration = the dense-matrix PDHG of its formulas (both models, nn)") {
    for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
        for (bool nn : {false, true}) {
            const Problem P = model == ConvModel::kCyclic ? make_problem(model, 12, 10, 5, 5, 21)
                                                          : make_problem(model, 9, 11, 4, 3, 23);
            const ConvolutionOperator op(P.psf, P.g);
            const Plane x0 = random_plane(P.g.work_rows, P.g.work_cols, 25, 0.0, 1.0);
            TvqcOptions o;
            o.eps = 0.5 * std::sqrt(P.p.square().sum());
            o.nonnegative = nn;
            o.max_iterations = 40;
            o.tolerance = 0.0;
            const DecodeResult r = solve_tvqc(op, P.p, o, &x0);
            const auto ref = dense_pdhg(P, x0, o.eps, nn, o.max_iterations);
            REQUIRE(r.history.size() == ref.size());
            const int model_id = static_cast<int>(model);
            const bool nonneg = nn;
            INFO("model " << model_id << " nonnegative " << nonneg);
            for (std::size_t k = 0; k < ref.size(); ++k) {
                CHECK(std::fabs(r.history[k].objective - ref[k].first) <=
                      kDenseIterationTol * std::max(1.0, ref[k].first));
                CHECK(std::fabs(r.history[k].residual - ref[k].second) <=
                      kDenseIterationTol * std::max(1.0, ref[k].second));
            }
        }
    }
}
