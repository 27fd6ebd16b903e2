#include <doctest/doctest.h>

#include <cmath>
#include <tuple>
#include <utility>

#include "bench/decode_bench.hpp"
#include "core/errors/error.hpp"
#include "decode/solvers/gradient.hpp"
#include "decode/solvers/tv_l2.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// ADMM run to a 1e-10 relative change against the smoothed-TV Newton reference (whose own error
// is below lambda N 1e-9): the required bound on the objective gap.
constexpr double kTvObjectiveTol = 1e-4;

// A piecewise-constant scene (two blocks) blurred by a positive PSF, plus seeded noise.
struct Problem {
    Plane psf, x_true, p;
    ConvGeometry g;
};

Problem make_problem(ConvModel model, int R, int C, int pr, int pc, unsigned seed) {
    Problem P;
    P.g = make_conv_geometry(model, R, C, pr, pc);
    P.psf = random_plane(pr, pc, seed, 0.0, 1.0);
    P.psf /= P.psf.sum();
    P.x_true = Plane::Zero(P.g.work_rows, P.g.work_cols);
    P.x_true.block(P.g.crop_row + R / 4, P.g.crop_col + C / 3, R / 2, C / 2) = 1.0;
    P.x_true.block(P.g.crop_row + 1, P.g.crop_col + 1, 3, 3) = 0.5;
    const Eigen::MatrixXd A = dense_model(P.psf, P.g);
    P.p = as_plane(A * as_vector(P.x_true), R, C) + 0.02 * random_plane(R, C, seed + 1, -1.0, 1.0);
    return P;
}

TvL2Options tight(double lambda) {
    TvL2Options o;
    o.lambda = lambda;
    o.max_iterations = 20000;
    o.tolerance = 1e-10;
    o.record_history = false;
    return o;
}

}  // namespace

TEST_CASE("TV-L2 reaches the smoothed-TV Newton reference objective (cyclic 16 x 16, 13 x 11)") {
    for (const auto& t : {std::tuple{16, 16, 1u}, {13, 11, 2u}}) {
        const int R = std::get<0>(t), C = std::get<1>(t);
        const unsigned seed = std::get<2>(t);
        const Problem P = make_problem(ConvModel::kCyclic, R, C, 5, 4, seed);
        const double lambda = 0.02;
        const Eigen::MatrixXd A = dense_model(P.psf, P.g);
        const Plane x_ref = as_plane(smoothed_tv_reference(A, as_vector(P.p), lambda, R, C), R, C);
        const ConvolutionOperator op(P.psf, P.g);
        const double f_ref = tv_l2_objective(op, P.p, x_ref, lambda);
        const DecodeResult r = solve_tv_l2(op, P.p, tight(lambda));
        INFO(R << " x " << C << ": admm " << r.objective << " ref " << f_ref << " after "
               << r.iterations);
        CHECK(r.converged);
        CHECK(r.objective <= f_ref * (1.0 + kTvObjectiveTol));
        CHECK(r.objective >= f_ref * (1.0 - kTvObjectiveTol));
        CHECK_CLOSE(r.objective, tv_l2_objective(op, P.p, r.image, lambda), 1e-14);
    }
}

TEST_CASE("TV-L2 on the linear model reaches the Newton reference with the dense crop operator") {
    const Problem P = make_problem(ConvModel::kLinear, 8, 9, 3, 4, 3);
    const double lambda = 0.02;
    const Eigen::MatrixXd A = dense_model(P.psf, P.g);
    const Plane x_ref =
        as_plane(smoothed_tv_reference(A, as_vector(P.p), lambda, P.g.work_rows, P.g.work_cols),
                 P.g.work_rows, P.g.work_cols);
    const ConvolutionOperator op(P.psf, P.g);
    const double f_ref = tv_l2_objective(op, P.p, x_ref, lambda);
    const DecodeResult r = solve_tv_l2(op, P.p, tight(lambda));
    INFO("admm " << r.objective << " ref " << f_ref << " after " << r.iterations);
    CHECK(r.image.rows() == P.g.work_rows);
    CHECK(r.objective <= f_ref * (1.0 + kTvObjectiveTol));
    CHECK(r.objective >= f_ref * (1.0 - kTvObjectiveTol));
}

TEST_CASE("TV-L2 on the linear model: the Newton reference on several geometries, in float32") {
    // The crop split's state lives on the capture window only (decode/solvers/tv_l2.cpp): windows
    // that touch the grid's edge on one side only (odd sizes), PSFs wider than the capture, and a
    // float32 run held to the double run's objective.
    const std::tuple<int, int, int, int, unsigned> shapes[] = {
        {7, 10, 5, 3, 21}, {9, 6, 10, 7, 22}, {10, 11, 2, 9, 23}};
    for (const auto& t : shapes) {
        // Copies (clang 14 cannot capture structured bindings in INFO's lambda).
        const int R = std::get<0>(t), C = std::get<1>(t), pr = std::get<2>(t), pc = std::get<3>(t);
        const unsigned seed = std::get<4>(t);
        const Problem P = make_problem(ConvModel::kLinear, R, C, pr, pc, seed);
        const double lambda = 0.01;
        const Eigen::MatrixXd A = dense_model(P.psf, P.g);
        const Plane x_ref =
            as_plane(smoothed_tv_reference(A, as_vector(P.p), lambda, P.g.work_rows, P.g.work_cols),
                     P.g.work_rows, P.g.work_cols);
        const ConvolutionOperator op(P.psf, P.g);
        const double f_ref = tv_l2_objective(op, P.p, x_ref, lambda);
        const DecodeResult d = solve_tv_l2(op, P.p, tight(lambda));
        TvL2Options single = tight(lambda);
        single.single_precision = true;
        single.max_iterations = 3000;
        single.tolerance = 0.0;
        const DecodeResult f = solve_tv_l2(op, P.p, single);
        INFO(R << " x " << C << ", psf " << pr << " x " << pc << ": admm " << d.objective
               << " float32 " << f.objective << " ref " << f_ref << " after " << d.iterations);
        CHECK(d.converged);
        CHECK(d.objective <= f_ref * (1.0 + kTvObjectiveTol));
        CHECK(d.objective >= f_ref * (1.0 - kTvObjectiveTol));
        // float32: the objective within 1e-4 of the optimum (float rounding of the iterates,
        // ~1e-7 relative, bounds the gap from above far below this).
        CHECK(f.objective <= f_ref * (1.0 + 1e-4));
    }
}

TEST_CASE("TV-L2 linear with x >= 0: between the unconstrained optimum and its clipped copy") {
    const Problem P = make_problem(ConvModel::kLinear, 9, 8, 4, 5, 24);
    const ConvolutionOperator op(P.psf, P.g);
    const double lambda = 0.02;
    const DecodeResult free = solve_tv_l2(op, P.p, tight(lambda));
    for (bool single : {false, true}) {
        TvL2Options o = tight(lambda);
        o.nonnegative = true;
        o.single_precision = single;
        if (single) {
            o.max_iterations = 3000;
            o.tolerance = 0.0;
        }
        const DecodeResult nn = solve_tv_l2(op, P.p, o);
        INFO("single " << single << ": " << nn.objective << " free " << free.objective);
        CHECK(nn.image.minCoeff() >= 0.0);
        CHECK(nn.objective >= free.objective * (1.0 - kTvObjectiveTol));
        CHECK(nn.objective <=
              tv_l2_objective(op, P.p, free.image.max(0.0), lambda) * (1.0 + kTvObjectiveTol));
    }
}

TEST_CASE("TV-L2 with x >= 0: feasible, between the unconstrained optimum and its clipped copy") {
    const Problem P = make_problem(ConvModel::kCyclic, 16, 16, 5, 5, 4);
    const ConvolutionOperator op(P.psf, P.g);
    const double lambda = 0.05;
    const DecodeResult free = solve_tv_l2(op, P.p, tight(lambda));
    TvL2Options o = tight(lambda);
    o.nonnegative = true;
    const DecodeResult nn = solve_tv_l2(op, P.p, o);
    CHECK(nn.image.minCoeff() >= 0.0);
    CHECK(nn.objective >= free.objective * (1.0 - kTvObjectiveTol));
    CHECK(nn.objective <=
          tv_l2_objective(op, P.p, free.image.max(0.0), lambda) * (1.0 + kTvObjectiveTol));
}

TEST_CASE("TV-L2 limits: lambda -> 0 is least squares, huge lambda is the best constant") {
    const Plane psf = random_psf(4, 4, 5);  // |H| >= 1/3: least squares is the exact inverse
    const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, 12, 10, 4, 4);
    const ConvolutionOperator op(psf, g);
    const Plane x_true = random_plane(12, 10, 6, -1.0, 1.0);
    const Plane p = op.apply(x_true);
    TvL2Options o = tight(1e-12);
    const DecodeResult small = solve_tv_l2(op, p, o);
    constexpr double kLeastSquaresTol = 1e-6;  // lambda TV bias ~1e-10 plus ADMM stopping error
    CHECK(max_rel_error(small.image, x_true) <= kLeastSquaresTol);

    o = tight(1e6);
    const DecodeResult big = solve_tv_l2(op, p, o);
    // argmin_c 1/2 ||A c 1 - p||^2 = mean(p) / sum(psf) = mean(p) for a unit-sum PSF.
    const double c = p.mean() / psf.sum();
    constexpr double kConstantTol = 1e-8;  // TV term forces exact flatness; ADMM stopping error
    CHECK((big.image - c).abs().maxCoeff() <= kConstantTol * std::max(1.0, std::abs(c)));
    CHECK(is_all_finite(big.image));
}

TEST_CASE("TV-L2 history, warm start and iteration cap") {
    const Problem P = make_problem(ConvModel::kCyclic, 16, 16, 5, 5, 7);
    const ConvolutionOperator op(P.psf, P.g);
    TvL2Options o;
    o.lambda = 0.02;
    o.tolerance = 1e-6;
    o.max_iterations = 3000;
    const DecodeResult cold = solve_tv_l2(op, P.p, o);
    REQUIRE(cold.history.size() == static_cast<std::size_t>(cold.iterations));
    for (std::size_t i = 1; i < cold.history.size(); ++i) {
        CHECK(cold.history[i].iteration == cold.history[i - 1].iteration + 1);
        CHECK(cold.history[i].seconds >= cold.history[i - 1].seconds);
    }
    CHECK_CLOSE(cold.history.back().objective, cold.objective, 1e-12);
    CHECK_CLOSE(cold.history.back().residual, cold.residual, 1e-12);
    CHECK(cold.history.back().objective < cold.history.front().objective);

    const DecodeResult warm = solve_tv_l2(op, P.p, o, &cold.image);
    INFO("warm " << warm.iterations << " cold " << cold.iterations);
    CHECK(warm.iterations < cold.iterations);

    // The records describe the returned estimate (model cyclic or linear; with x >= 0 they
    // describe the ADMM iterate x, see tv_l2.hpp).
    for (ConvModel m : {ConvModel::kCyclic, ConvModel::kLinear}) {
        for (bool nn : {false, true}) {
            const Problem Q = make_problem(m, 12, 10, 4, 3, 9);
            const ConvolutionOperator qop(Q.psf, Q.g);
            TvL2Options q;
            q.lambda = 0.02;
            q.nonnegative = nn;
            q.max_iterations = 25;
            q.tolerance = 0.0;
            const DecodeResult h = solve_tv_l2(qop, Q.p, q);
            INFO("model " << int(m) << " nonnegative " << nn);
            REQUIRE(h.history.size() == 25);
            for (const IterationRecord& rec : h.history) CHECK(std::isfinite(rec.objective));
            if (nn) {  // records follow the ADMM iterate x; the estimate is w = max(x + v, 0)
                CHECK(h.objective <= h.history.front().objective);
            } else {
                CHECK_CLOSE(h.history.back().objective, h.objective, 1e-12);
                CHECK_CLOSE(h.history.back().residual, h.residual, 1e-12);
            }
        }
    }

    o.max_iterations = 5;
    o.record_history = false;
    const DecodeResult capped = solve_tv_l2(op, P.p, o);
    CHECK(capped.iterations == 5);
    CHECK_FALSE(capped.converged);
    CHECK(capped.history.empty());
}

TEST_CASE("TV-L2 validates lambda, rho, sizes and warm start") {
    const Problem P = make_problem(ConvModel::kCyclic, 8, 8, 3, 3, 8);
    const ConvolutionOperator op(P.psf, P.g);
    TvL2Options o;
    o.lambda = -1.0;
    CHECK_THROWS_WITH_AS(solve_tv_l2(op, P.p, o), doctest::Contains("lambda"), InvalidInput);
    o.lambda = 0.1;
    o.rho = -2.0;
    CHECK_THROWS_WITH_AS(solve_tv_l2(op, P.p, o), doctest::Contains("rho"), InvalidInput);
    o.rho = 0.0;
    o.max_iterations = -1;
    CHECK_THROWS_WITH_AS(solve_tv_l2(op, P.p, o), doctest::Contains("max_iterations"),
                         InvalidInput);
    o.max_iterations = 10;
    const Plane bad = Plane::Zero(7, 8);
    CHECK_THROWS_WITH_AS(solve_tv_l2(op, P.p, o, &bad), doctest::Contains("warm_start"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(solve_tv_l2(op, bad, o), doctest::Contains("capture"), InvalidInput);
}

TEST_CASE("TV-L2: the AVX2 build of the fused pass gives the baseline build's bits") {
    // Independent of the CPU's features only when they agree bit for bit: every precision,
    // model, constraint and record setting, over enough iterations for several adaptations.
    if (!tv_l2_avx2_available()) {
        MESSAGE("no AVX2 on this CPU: only the baseline build runs");
        return;
    }
    for (ConvModel m : {ConvModel::kCyclic, ConvModel::kLinear}) {
        const Problem P = make_problem(m, 24, 20, 5, 4, 11);
        const ConvolutionOperator op(P.psf, P.g);
        for (bool single : {false, true}) {
            for (bool nn : {false, true}) {
                for (bool records : {false, true}) {
                    TvL2Options o;
                    o.lambda = 0.01;
                    o.max_iterations = 40;
                    o.tolerance = 0.0;
                    o.single_precision = single;
                    o.nonnegative = nn;
                    o.record_history = records;
                    set_tv_l2_avx2(false);
                    const DecodeResult base = solve_tv_l2(op, P.p, o);
                    set_tv_l2_avx2(true);
                    const DecodeResult avx = solve_tv_l2(op, P.p, o);
                    INFO("model " << int(m) << " single " << single << " nonnegative " << nn
                                  << " records " << records);
                    CHECK((base.image == avx.image).all());
                    CHECK(base.objective == avx.objective);
                }
            }
        }
    }
}

TEST_CASE("TV-L2 on the paper problem: iterations to 0.2 dB of converged (bench tv_l2_to_0.2dB)") {
    // A regression guard on the bench's convergence figure (an iteration count, not a time): the
    // counts measured when the cyclic over-relaxation became 1.95 (at 1.8: 6, 18, 34). The
    // target for lambda 1e-3 is 12 (not met; docs/limits.md).
    constexpr int kSize = 128;
    constexpr double kSnrDb = 30.0, kWithinDb = 0.2;
    constexpr int kCap = 40;
    // One iteration of slack: the clang (sanitized) build rounds differently and crosses the
    // 0.2 dB line one iteration later at lambda 1e-4 (7 against 6). A return to 1.8 still fails
    // at lambda 1e-2 (34 > 33).
    constexpr int kCompilerSlack = 1;
    const std::pair<double, int> cases[] = {
        {1e-4, 6 + kCompilerSlack}, {1e-3, 17 + kCompilerSlack}, {1e-2, 32 + kCompilerSlack}};
    for (const auto& c : cases) {
        const double lambda = c.first;
        const int most = c.second;
        const TvConvergence t =
            tv_l2_iterations_to_converged(kSize, lambda, kSnrDb, kWithinDb, kCap, 1);
        INFO("lambda " << lambda << " iterations " << t.iterations);
        CHECK(t.reached);
        CHECK(t.iterations <= most);
    }
}

TEST_CASE("TV-L2 linear: a PSF scaled by a power of two gives the same iterates, scaled back") {
    // H -> c H, lambda -> c lambda: every iterate x_k -> x_k / c when the penalties follow the
    // PSF's scale (rho ~ c^2 for the gradient and non-negativity splits, the crop split's rho_s
    // unchanged: the s-step weighs it against the data term in capture units). A power of two
    // scales every rounding exactly, so the estimates agree to the last bits; a crop penalty that
    // followed c^2 took another path (and adapted differently).
    const Problem P = make_problem(ConvModel::kLinear, 24, 20, 7, 9, 31);
    const double c = 1024.0, lambda = 0.01;
    TvL2Options o;
    o.lambda = lambda;
    o.nonnegative = true;
    o.max_iterations = 60;  // past several penalty adaptations
    o.tolerance = 0.0;
    o.record_history = false;
    const DecodeResult base = solve_tv_l2(ConvolutionOperator(P.psf, P.g), P.p, o);
    o.lambda = c * lambda;
    const Plane scaled_psf = c * P.psf;
    const DecodeResult scaled = solve_tv_l2(ConvolutionOperator(scaled_psf, P.g), P.p, o);
    CHECK(scaled.iterations == base.iterations);
    CHECK((scaled.image * c - base.image).abs().maxCoeff() <= 1e-12 * base.image.abs().maxCoeff());
}
