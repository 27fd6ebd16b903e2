// decode_plane: input validation naming the option, and the facade's plumbing (working grid,
// crop, warm start, per-frequency NSR) against the algorithm objects it wraps.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <limits>

#include "core/errors/error.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/tikhonov.hpp"
#include "decode/solvers/wiener.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Same computation along the facade and along the direct object: rounding only.
constexpr double kSamePathTol = 1e-14;
// The closed-form residual and penalty summed over the spectrum (Parseval) against the same
// figures computed in the spatial domain from the returned image: two roundings of sums of N
// terms whose size is that of the sum (nsr and lambda keep the residual a sizeable part of ||p||).
constexpr double kParsevalTol = 1e-10;
// Single precision: the sums come from the float spectrum, the reference from the float image.
constexpr double kParsevalSingleTol = 1e-5;

void check_rejects(const Plane& capture, const Plane& psf, const DecodeOptions& o,
                   const char* field) {
    INFO("expecting an error naming " << field);
    CHECK_THROWS_WITH_AS(decode_plane(capture, psf, o), doctest::Contains(field), InvalidInput);
}

}  // namespace

TEST_CASE("decode_plane rejects bad inputs, naming the option") {
    const Plane p = random_plane(8, 8, 80, 0.0, 1.0);
    const Plane psf = random_psf(3, 3, 81);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    DecodeOptions o;
    Plane bad = p;
    bad(2, 3) = nan;
    check_rejects(bad, psf, o, "capture");
    bad = p;
    bad(0, 0) = std::numeric_limits<double>::infinity();
    check_rejects(bad, psf, o, "capture");
    Plane bad_psf = psf;
    bad_psf(1, 1) = nan;
    check_rejects(p, bad_psf, o, "psf");
    check_rejects(p, Plane::Zero(3, 3), o, "psf sum");
    check_rejects(p, -psf, o, "psf sum");
    check_rejects(p, random_psf(9, 3, 82), o, "psf");  // larger than the cyclic working size
    check_rejects(Plane(0, 0), psf, o, "capture");

    // One option out of range at a time, on fresh defaults.
    auto with = [&](auto set, const char* field) {
        DecodeOptions fresh;
        set(fresh);
        check_rejects(p, psf, fresh, field);
    };
    // Each struct's validate() names the field as a reference the faces spell (`--nsr`, nsr=).
    with([](DecodeOptions& x) { x.wiener.nsr = -0.1; }, "`wiener_nsr`");
    with(
        [](DecodeOptions& x) {
            x.method = DecodeMethod::kTikhonov;
            x.tikhonov.lambda = -1.0;
        },
        "`lambda`");
    with(
        [](DecodeOptions& x) {
            x.method = DecodeMethod::kTv;
            x.tv.lambda = std::numeric_limits<double>::quiet_NaN();
        },
        "`lambda`");
    with(
        [](DecodeOptions& x) {
            x.method = DecodeMethod::kTvqc;
            x.tvqc.eps = -1.0;
        },
        "`eps`");
    with(
        [](DecodeOptions& x) {
            x.method = DecodeMethod::kTvqc;
            x.tvqc.noise_sigma = -1.0;
        },
        "`noise_sigma`");
    with(
        [](DecodeOptions& x) {
            x.method = DecodeMethod::kTvqc;
            x.tvqc.eps = 0.1;
            x.tvqc.noise_sigma = 0.1;
        },
        "`noise_sigma`");  // both: one must go
    with([](DecodeOptions& x) { x.iterative.max_iterations = -3; }, "`iterations`");
    with([](DecodeOptions& x) { x.iterative.tolerance = -1e-3; }, "`tolerance`");
    with([](DecodeOptions& x) { x.iterative.warm_start = Plane::Zero(7, 8); }, "warm_start");
    with([](DecodeOptions& x) { x.wiener.nsr_per_frequency = Plane::Constant(8, 9, 0.1); },
         "`nsr_map`");
    with([](DecodeOptions& x) { x.wiener.nsr_per_frequency = Plane::Constant(8, 8, -0.1); },
         "`nsr_map`");
    with([](DecodeOptions& x) { x.method = DecodeMethod::kTvqc; }, "eps");  // no eps, no sigma
    // An enum value outside the table is an error, never a fall-through to some method.
    with([](DecodeOptions& x) { x.method = static_cast<DecodeMethod>(17); }, "method");
    with([](DecodeOptions& x) { x.model = static_cast<ConvModel>(5); }, "model");
    // A method reads its own struct only: a bad value in another method's struct is not read.
    {
        DecodeOptions w;
        w.tv.lambda = -1.0;
        w.tvqc.eps = -1.0;
        CHECK_NOTHROW(decode_plane(p, psf, w));
    }
    o.method = DecodeMethod::kRichardsonLucy;
    Plane neg_psf = psf;
    neg_psf(0, 0) = -0.01;
    check_rejects(p, neg_psf, o, "psf");
}

TEST_CASE("decode_plane Wiener equals WienerFilter, scalar and per-frequency NSR") {
    const Plane p = random_plane(12, 9, 83, -1.0, 1.0);
    const Plane psf = random_psf(4, 3, 84);
    DecodeOptions o;
    o.wiener.nsr = 0.03;
    const DecodeResult r = decode_plane(p, psf, o);
    CHECK(r.image.rows() == 12);
    CHECK(r.image.cols() == 9);
    CHECK(r.history.empty());
    CHECK(max_rel_error(r.image, WienerFilter(psf, 12, 9, 0.03).apply(p)) <= kSamePathTol);
    CHECK_CLOSE(r.objective, r.residual * r.residual + 0.03 * r.image.square().sum(), 1e-12);

    o.wiener.nsr_per_frequency = Plane::Constant(12, 9, 0.03);
    const DecodeResult rf = decode_plane(p, psf, o);
    CHECK(max_rel_error(rf.image, r.image) <= 1e-12);
    CHECK_CLOSE(rf.objective, r.objective, 1e-12);  // Parseval form of nsr ||x||^2
}

TEST_CASE("closed form: residual and objective from the spectrum equal the spatial ones") {
    for (const auto& sz : {std::pair{12, 9}, std::pair{16, 16}, std::pair{7, 13}}) {
        const int R = sz.first, C = sz.second;
        const Plane p = random_plane(R, C, 91, -1.0, 1.0);
        const Plane psf = random_psf(3, 4, 92);
        const Eigen::MatrixXd A = dense_circulant(psf, R, C);
        Plane nsr_pf = random_plane(R, C, 93, 0.01, 0.2);  // asymmetric on purpose
        for (int variant = 0; variant < 5; ++variant) {
            for (bool single : {false, true}) {
                DecodeOptions o;
                o.single_precision = single;
                o.wiener.nsr = 0.05;
                o.tikhonov.lambda = 0.07;
                if (variant == 1) o.wiener.nsr_per_frequency = nsr_pf;
                if (variant >= 2) o.method = DecodeMethod::kTikhonov;
                o.tikhonov.regulariser =
                    variant == 3 ? TikhonovRegulariser::kIdentity : TikhonovRegulariser::kGradient;
                if (variant == 4) o.tikhonov.lambda = 0.0;  // the gradient pseudo-inverse
                const DecodeResult r = decode_plane(p, psf, o);
                const Eigen::VectorXd e = A * as_vector(r.image) - as_vector(p);
                double penalty = 0.0;
                if (variant == 0) penalty = o.wiener.nsr * r.image.square().sum();
                if (variant == 1) {  // the full-spectrum sum, with the full spectrum expanded
                    const Fft2 fft(R, C);
                    const ComplexPlane X = expand_half_spectrum(fft.forward(r.image), C);
                    penalty = (nsr_pf * X.abs2()).sum() / double(R * C);
                }
                if (variant >= 2)
                    penalty = tikhonov_penalty(r.image, o.tikhonov.lambda, o.tikhonov.regulariser);
                const double tol = single ? kParsevalSingleTol : kParsevalTol;
                INFO(R << " x " << C << " variant " << variant << " single " << single);
                if (variant == 4) {  // exact fit: both residuals are rounding, ~0 against ||p||
                    const double pn = p.matrix().norm();
                    CHECK(r.residual <= tol * pn);
                    CHECK(e.norm() <= tol * pn);
                    continue;
                }
                CHECK_CLOSE(r.residual, e.norm(), tol);
                CHECK_CLOSE(r.objective, e.squaredNorm() + penalty, tol);
            }
        }
    }
}

TEST_CASE("spectrum weights: multiplicity and folding reproduce full-spectrum sums") {
    for (const auto& sz : {std::pair{6, 8}, std::pair{5, 7}}) {
        const int R = sz.first, C = sz.second;
        const Plane x = random_plane(R, C, 94, -1.0, 1.0);
        const Plane w = random_plane(R, C, 95, 0.0, 1.0);
        const ComplexPlane half = Fft2(R, C).forward(x);
        const ComplexPlane full = expand_half_spectrum(half, C);
        CHECK_CLOSE((half_spectrum_multiplicity(R, C) * half.abs2()).sum(), full.abs2().sum(),
                    kSamePathTol * 100);
        CHECK_CLOSE((fold_full_spectrum_weight(w) * half.abs2()).sum(), (w * full.abs2()).sum(),
                    kSamePathTol * 100);
    }
}

TEST_CASE("linear model: Wiener on the padded grid, image cropped to the capture size") {
    const Plane p = random_plane(10, 12, 85, -1.0, 1.0);
    const Plane psf = random_psf(10, 12, 86);  // DiffuserCam-like: PSF as large as the capture
    DecodeOptions o;
    o.model = ConvModel::kLinear;
    o.wiener.nsr = 0.01;
    const DecodeResult r = decode_plane(p, psf, o);
    const ConvGeometry g = make_conv_geometry(ConvModel::kLinear, 10, 12, 10, 12);
    const Plane ref = crop_to_capture(
        g, WienerFilter(psf, g.work_rows, g.work_cols, 0.01).apply(pad_to_work(g, p)));
    CHECK(r.image.rows() == 10);
    CHECK(r.image.cols() == 12);
    CHECK(max_rel_error(r.image, ref) <= kSamePathTol);
}

TEST_CASE("iterative methods through the facade: history, warm start of the working size") {
    const Plane p = random_plane(16, 16, 87, 0.0, 1.0);
    const Plane psf = random_psf(5, 5, 88);
    for (DecodeMethod m : {DecodeMethod::kTv, DecodeMethod::kTvqc, DecodeMethod::kRichardsonLucy}) {
        for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
            DecodeOptions o;
            o.method = m;
            o.model = model;
            o.tvqc.eps = 0.05;
            o.iterative.max_iterations = 40;
            const DecodeResult r = decode_plane(p, psf, o);
            INFO("method " << int(m) << " model " << int(model));
            CHECK(r.image.rows() == 16);
            CHECK(r.image.cols() == 16);
            CHECK(r.history.size() == static_cast<std::size_t>(r.iterations));
            CHECK(r.iterations >= 1);
            CHECK(r.seconds >= 0.0);
            const ConvGeometry g = make_conv_geometry(model, 16, 16, 5, 5);
            o.iterative.warm_start = Plane::Constant(g.work_rows, g.work_cols, 0.5);
            o.iterative.record_history = false;
            const DecodeResult w = decode_plane(p, psf, o);
            CHECK(w.history.empty());
            CHECK(is_all_finite(w.image));
        }
    }
}

TEST_CASE(
    "records do not change the estimate: every iterative method, both models, both "
    "precisions give the same bits with and without history") {
    // The CLI records only for --stats / --json (records cost an objective per iteration), so
    // the image must not depend on them.
    const Plane p = random_plane(24, 20, 91, 0.0, 1.0);
    const Plane psf = random_psf(5, 5, 92);
    for (DecodeMethod m : {DecodeMethod::kTv, DecodeMethod::kTvqc, DecodeMethod::kRichardsonLucy}) {
        for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
            for (bool single : {false, true}) {
                DecodeOptions o;
                o.method = m;
                o.model = model;
                o.tvqc.eps = 0.05;
                o.iterative.max_iterations = 30;
                o.single_precision = single;
                o.iterative.record_history = true;
                const DecodeResult with = decode_plane(p, psf, o);
                o.iterative.record_history = false;
                const DecodeResult without = decode_plane(p, psf, o);
                INFO("method " << int(m) << " model " << int(model) << " single " << single);
                CHECK(with.iterations == without.iterations);
                CHECK((with.image.array() == without.image.array()).all());
                CHECK(with.residual == without.residual);
            }
        }
    }
}

TEST_CASE("a raised stop flag ends every iterative method after the iteration it is in") {
    const Plane p = random_plane(16, 16, 89, 0.0, 1.0);
    const Plane psf = random_psf(5, 5, 90);
    for (DecodeMethod m : {DecodeMethod::kTv, DecodeMethod::kTvqc, DecodeMethod::kRichardsonLucy}) {
        for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
            INFO("method " << int(m) << " model " << int(model));
            DecodeOptions o;
            o.method = m;
            o.model = model;
            o.tvqc.eps = 0.05;
            o.iterative.max_iterations = 1000;
            o.iterative.tolerance = 0.0;  // never converges on its own
            std::atomic<bool> stop{false};
            o.iterative.stop = &stop;
            const DecodeResult full = decode_plane(p, psf, o);
            CHECK_FALSE(full.interrupted);
            CHECK(full.iterations == 1000);
            stop.store(true);
            const DecodeResult cut = decode_plane(p, psf, o);
            CHECK(cut.interrupted);
            CHECK_FALSE(cut.converged);
            CHECK(cut.iterations == 1);
            CHECK(cut.history.size() == 1);
            CHECK(is_all_finite(cut.image));
            // The same first iterate as an uninterrupted one-iteration run.
            o.iterative.stop = nullptr;
            o.iterative.max_iterations = 1;
            const DecodeResult one = decode_plane(p, psf, o);
            CHECK((cut.image - one.image).abs().maxCoeff() == 0.0);
        }
    }
}
