// Named stability cases, run through decode_plane for every method: no NaN or Inf,
// no divergence, and the documented limit behaviour.
#include <doctest/doctest.h>

#include <cmath>

#include "core/fft/fft.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

const DecodeMethod kAllMethods[] = {DecodeMethod::kWiener, DecodeMethod::kTikhonov,
                                    DecodeMethod::kTv, DecodeMethod::kTvqc,
                                    DecodeMethod::kRichardsonLucy};

DecodeOptions options_for(DecodeMethod m, ConvModel model = ConvModel::kCyclic) {
    DecodeOptions o;
    o.method = m;
    o.model = model;
    o.tikhonov.lambda = 1e-2;
    o.tv.lambda = 1e-2;
    o.tvqc.eps = 0.01;
    o.iterative.max_iterations = 300;
    return o;
}

}  // namespace

TEST_CASE("stability: NSR = 0 on a PSF with exact spectral zeros drops those frequencies") {
    // PSF [1/2 1/2]: H vanishes on column l = C / 2 only; elsewhere |H|^2 >= cos^2(3 pi / 8).
    Plane psf(1, 2);
    psf << 0.5, 0.5;
    const Plane x_true = random_plane(8, 8, 70, -1.0, 1.0);
    const ConvolutionOperator op(psf, make_conv_geometry(ConvModel::kCyclic, 8, 8, 1, 2));
    const Plane p = op.apply(x_true);
    DecodeOptions o = options_for(DecodeMethod::kWiener);
    o.wiener.nsr = 0.0;
    const DecodeResult r = decode_plane(p, psf, o);
    const Fft2 fft(8, 8);
    ComplexPlane spec = fft.forward(x_true);
    spec.col(4).setZero();
    constexpr double kInverseTol = 1e-12;  // exact inverse, |H|^2 >= 0.146
    CHECK(is_all_finite(r.image));
    CHECK(max_rel_error(r.image, fft.inverse(spec)) <= kInverseTol);
}

TEST_CASE("stability: NSR 1e-12 and 1e12") {
    const Plane psf = random_psf(3, 3, 71);
    const Plane x_true = random_plane(9, 9, 72, -1.0, 1.0);
    const ConvolutionOperator op(psf, make_conv_geometry(ConvModel::kCyclic, 9, 9, 3, 3));
    const Plane p = op.apply(x_true);
    DecodeOptions o = options_for(DecodeMethod::kWiener);
    o.wiener.nsr = 1e-12;
    CHECK(max_rel_error(decode_plane(p, psf, o).image, x_true) <= 1e-10);  // bias NSR/|H|^2
    o.wiener.nsr = 1e12;  // x -> A^T p / NSR, relative correction |H|^2 / NSR <= 1e-12
    CHECK(max_rel_error(decode_plane(p, psf, o).image, op.adjoint(p) / 1e12) <= 1e-10);
}

TEST_CASE("stability: constant, all-zero and saturated captures, every method and model") {
    const Plane psf = random_psf(5, 5, 73);
    for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
        for (DecodeMethod m : kAllMethods) {
            const DecodeOptions o = options_for(m, model);
            INFO("method " << int(m) << " model " << int(model));
            const DecodeResult zero = decode_plane(Plane::Zero(12, 10), psf, o);
            CHECK((zero.image.abs() <= 1e-300).all());

            const DecodeResult flat = decode_plane(Plane::Constant(12, 10, 0.7), psf, o);
            CHECK(is_all_finite(flat.image));
            if (model == ConvModel::kCyclic && m != DecodeMethod::kTvqc) {
                // Cyclic, unit-sum PSF: Wiener and identity Tikhonov shrink the constant by
                // 1 / (1 + nsr or lambda); TV-L2 and RL fit it exactly (no gradient, no misfit).
                // TVQC may return any constant inside the constraint.
                const double shrink = m == DecodeMethod::kWiener ? 1.0 / (1.0 + o.wiener.nsr)
                                      : m == DecodeMethod::kTikhonov
                                          ? 1.0 / (1.0 + o.tikhonov.lambda)
                                          : 1.0;
                CHECK((flat.image - 0.7 * shrink).abs().maxCoeff() <= 1e-6);
            }
            if (m == DecodeMethod::kTvqc && model == ConvModel::kCyclic) {
                CHECK(flat.objective <= 1e-6);  // a constant: TV = 0
            }

            Plane sat = random_plane(12, 10, 74, 0.0, 65535.0);
            sat.block(2, 2, 6, 6).setConstant(65535.0);
            const DecodeResult s = decode_plane(sat, psf, o);
            CHECK(is_all_finite(s.image));
            CHECK(std::isfinite(s.objective));
            CHECK(std::isfinite(s.residual));
        }
    }
}

TEST_CASE("stability: all pinholes on one row (rank-deficient PSF), every method") {
    Plane psf = Plane::Zero(6, 6);
    psf(3, 0) = psf(3, 2) = psf(3, 4) = 1.0 / 3.0;  // H vanishes on columns l = C/3, 2C/3
    Plane x = Plane::Zero(12, 12);
    x.block(3, 3, 5, 6) = 1.0;
    const ConvolutionOperator op(psf, make_conv_geometry(ConvModel::kCyclic, 12, 12, 6, 6));
    const Plane p = op.apply(x);
    for (DecodeMethod m : kAllMethods) {
        DecodeOptions o = options_for(m);
        o.wiener.nsr = 0.0;
        o.tikhonov.lambda = 0.0;
        o.tv.lambda = 1e-3;
        o.tvqc.eps = 0.0;
        const DecodeResult r = decode_plane(p, psf, o);
        INFO("method " << int(m));
        CHECK(is_all_finite(r.image));
        // The data are in the range of A: every method but RL (not yet converged) fits them.
        if (m != DecodeMethod::kRichardsonLucy) {
            CHECK(r.residual <= 1e-2 * std::sqrt(p.square().sum()));
        }
    }
}

TEST_CASE("stability: lambda -> 0 and very large, through the facade") {
    const Plane psf = random_psf(4, 4, 75);
    const Plane p = random_plane(10, 10, 76, 0.0, 1.0);
    for (DecodeMethod m : {DecodeMethod::kTikhonov, DecodeMethod::kTv}) {
        for (double lambda : {0.0, 1e-12, 1e9}) {
            DecodeOptions o = options_for(m);
            o.tikhonov.lambda = lambda;
            o.tv.lambda = lambda;
            o.iterative.tolerance = 1e-9;
            o.iterative.max_iterations = 3000;
            const DecodeResult r = decode_plane(p, psf, o);
            INFO("method " << int(m) << " lambda " << lambda);
            CHECK(is_all_finite(r.image));
            if (lambda >= 1e9) {
                // Identity Tikhonov: x -> 0; TV: x -> the best constant mean(p).
                const double target = m == DecodeMethod::kTikhonov ? 0.0 : p.mean();
                CHECK((r.image - target).abs().maxCoeff() <= 1e-6);
            }
        }
    }
}
