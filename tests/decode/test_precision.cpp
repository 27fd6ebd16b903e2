// float32 against double on the same problem, and scale invariance / result checks of the
// decode facade.
#include <doctest/doctest.h>

#include <cmath>

#include "core/errors/error.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/tv_l2.hpp"
#include "decode/solvers/tvqc.hpp"
#include "tests/decode/test_decode_support.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Wiener / Tikhonov in float32: the capture, the filter and both transforms are rounded to
// float (relative 6e-8 each); the FFT pair adds ~eps_f log2 N; the filter's gain multiplies the
// capture's rounding. For these well-conditioned PSFs (|H| >= 1/3) the l2 error measured is
// ~3e-7; 5e-6 allows a 15x margin while still catching a double/float mix-up at 1e-3.
constexpr double kSingleClosedFormTol = 5e-6;
// TV-L2 in float32 after a fixed number of ADMM iterations: each iteration's rounding is
// damped by the contraction of ADMM, but the shrinkage is not smooth, so the gap is larger than
// for a filter; measured ~2e-5 at 256 x 256 and 60 iterations. 1e-3 relative l2 is far below
// what a person sees (0.01 dB) and far below the 0.2 dB the PSNR targets care about.
constexpr double kSingleTvTol = 1e-3;
// TVQC in float32 after 60 iterations: the iterates start at the double feasible point (cast
// to float: 6e-8 relative) and PDHG moves them by steps much smaller than x, each step carrying
// float rounding (eps_f log2 N of the step); the l2 error stays near the rounding of x itself:
// measured 8e-8 (cyclic and linear, 256 x 256). 1e-6 is a 12x margin; a float/double mix-up
// in a step or a wrong scale shows at >= 1e-4.
constexpr double kSingleTvqcTol = 1e-6;
// Richardson-Lucy in float32 after 60 iterations: the multiplicative update is smooth but not a
// contraction (EM converges sublinearly), so each iteration's rounding (two FFT pairs, ~eps_f
// log2 N) adds up rather than being damped: measured 2.0e-7 / 2.2e-7 (cyclic / linear).
// 3e-6 is a 14x margin.
constexpr double kSingleRlTol = 3e-6;
// Scale invariance: the facade divides by max |p| and multiplies back; both steps are exact in
// binary for powers of two, so a 2^k-scaled capture gives the same estimate times 2^k up to
// the rounding of the division by max |p| (a few ulps).
constexpr double kScaleTol = 1e-12;

double rel_l2(const Plane& a, const Plane& b) {
    return std::sqrt((a - b).square().sum() / std::max(b.square().sum(), 1e-300));
}

struct Problem {
    Plane psf, p;
};

Problem make(int n, unsigned seed) {
    Problem P;
    P.psf = random_psf(9, 9, seed);
    Plane x = Plane::Zero(n, n);
    x.block(n / 4, n / 3, n / 2, n / 3) = 1.0;
    x.block(n / 8, n / 8, n / 8, n / 8) = 0.5;
    const ConvolutionOperator op(P.psf, make_conv_geometry(ConvModel::kCyclic, n, n, 9, 9));
    P.p = op.apply(x) + 0.01 * random_plane(n, n, seed + 1, -1.0, 1.0);
    return P;
}

}  // namespace

TEST_CASE("single precision: wiener and tikhonov within kSingleClosedFormTol of double") {
    const Problem P = make(256, 3);
    for (DecodeMethod m : {DecodeMethod::kWiener, DecodeMethod::kTikhonov}) {
        DecodeOptions o;
        o.method = m;
        o.wiener.nsr = 1e-3;
        o.tikhonov.lambda = 1e-3;
        const Plane d = decode_plane(P.p, P.psf, o).image;
        o.single_precision = true;
        const Plane s = decode_plane(P.p, P.psf, o).image;
        INFO("method " << int(m));
        CHECK(rel_l2(s, d) <= kSingleClosedFormTol);
        CHECK(rel_l2(s, d) > 0.0);  // it really ran in float
    }
}

TEST_CASE("single precision: TV-L2 (cyclic and linear) within kSingleTvTol of double") {
    const bool sanitized = std::getenv("PINMASK_SANITIZED") != nullptr;
    const int n = sanitized ? 64 : 256;
    const Problem P = make(n, 5);
    for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
        DecodeOptions o;
        o.method = DecodeMethod::kTv;
        o.model = model;
        o.tv.lambda = 1e-3;
        o.tv.nonnegative = model == ConvModel::kLinear;
        o.iterative.max_iterations = 60;
        o.iterative.tolerance = 0.0;
        o.iterative.record_history = false;
        const Plane d = decode_plane(P.p, P.psf, o).image;
        o.single_precision = true;
        const Plane s = decode_plane(P.p, P.psf, o).image;
        INFO("model " << int(model));
        CHECK(rel_l2(s, d) <= kSingleTvTol);
    }
}

TEST_CASE("scale invariance: every method, captures scaled by 2^-900 .. 2^900") {
    const Problem P = make(24, 9);
    for (DecodeMethod m : {DecodeMethod::kWiener, DecodeMethod::kTikhonov, DecodeMethod::kTv,
                           DecodeMethod::kTvqc, DecodeMethod::kRichardsonLucy}) {
        DecodeOptions o;
        o.method = m;
        o.iterative.max_iterations = 30;
        o.iterative.tolerance = 0.0;
        o.tvqc.eps = 0.3;
        Plane p = P.p;
        if (m == DecodeMethod::kRichardsonLucy) p = p.max(0.0);
        const DecodeResult ref = decode_plane(p, P.psf, o);
        for (int k : {-900, -100, 100, 900}) {
            const double s = std::ldexp(1.0, k);
            DecodeOptions os = o;
            os.tv.lambda = o.tv.lambda * s;
            os.tvqc.eps = *o.tvqc.eps * s;
            const DecodeResult r = decode_plane(p * s, P.psf, os);
            INFO("method " << int(m) << " scale 2^" << k);
            REQUIRE(is_all_finite(r.image));
            CHECK(rel_l2(r.image / s, ref.image) <= kScaleTol);
            CHECK(r.converged == ref.converged);
            CHECK(r.constraint_met == ref.constraint_met);
        }
    }
}

TEST_CASE(
    "closed forms: a 2^k-scaled capture gives exactly 2^k times the estimate, both precisions") {
    // The closed forms scale by a power of two inside the filter's conversions (float32 always,
    // double outside 2^-100..2^100), so scaling is exact: bit for bit, not within a tolerance.
    // k = +-1000 puts the capture's peak near 1e301 / 1e-301 (the squared sums would overflow
    // or underflow unscaled).
    const Problem P = make(32, 21);
    for (DecodeMethod m : {DecodeMethod::kWiener, DecodeMethod::kTikhonov}) {
        for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
            for (bool single : {false, true}) {
                DecodeOptions o;
                o.method = m;
                o.model = model;
                o.single_precision = single;
                o.wiener.nsr = 1e-3;
                o.tikhonov.lambda = 1e-3;
                const DecodeResult ref = decode_plane(P.p, P.psf, o);
                for (int k : {-1000, -120, 120, 1000}) {
                    const double s = std::ldexp(1.0, k);
                    const DecodeResult r = decode_plane(P.p * s, P.psf, o);
                    INFO("method " << int(m) << " model " << int(model) << " single " << single
                                   << " scale 2^" << k);
                    CHECK((r.image == ref.image * s).all());
                    CHECK(r.residual == ref.residual * s);
                    if (std::abs(k) <= 120) CHECK(r.objective == ref.objective * s * s);
                }
            }
        }
    }
}

TEST_CASE("a capture with one pixel at 1e300 decodes to a finite estimate (no Inf image)") {
    Problem P = make(32, 13);
    P.p(5, 7) = 1e300;
    for (DecodeMethod m : {DecodeMethod::kWiener, DecodeMethod::kTv, DecodeMethod::kTvqc}) {
        DecodeOptions o;
        o.method = m;
        o.iterative.max_iterations = 20;
        o.tvqc.eps = 1e298;
        o.tv.lambda = 1e297;
        const DecodeResult r = decode_plane(P.p, P.psf, o);
        INFO("method " << int(m));
        CHECK(is_all_finite(r.image));
        CHECK(std::isfinite(r.residual));
    }
}

TEST_CASE("TVQC on a 1e30-scaled capture: finite, and converged only when the constraint holds") {
    const Problem P = make(32, 17);
    DecodeOptions o;
    o.method = DecodeMethod::kTvqc;
    o.tvqc.noise_sigma = 0.01 * 1e30;
    o.iterative.max_iterations = 400;
    const DecodeResult r = decode_plane(P.p * 1e30, P.psf, o);
    CHECK(is_all_finite(r.image));
    const double eps = tvqc_eps_from_sigma(*o.tvqc.noise_sigma, P.p.size());
    CHECK(r.constraint_met == (r.residual <= eps * (1.0 + 1e-6)));
    if (r.converged) CHECK(r.constraint_met);
}

TEST_CASE("TVQC that cannot meet its constraint in the iterations given says so") {
    // A 0/1 checkerboard with eps far below its distance to the range of a blurring PSF and a
    // handful of iterations: the exit point misses the constraint.
    Plane p(16, 16);
    for (int r = 0; r < 16; ++r)
        for (int c = 0; c < 16; ++c) p(r, c) = (r + c) % 2;
    Plane psf = Plane::Constant(4, 4, 1.0 / 16.0);  // a box: H = 0 at the checkerboard frequency
    DecodeOptions o;
    o.method = DecodeMethod::kTvqc;
    o.tvqc.eps = 1e-3;
    o.iterative.max_iterations = 5;
    const DecodeResult r = decode_plane(p, psf, o);
    CHECK(is_all_finite(r.image));
    CHECK_FALSE(r.constraint_met);
    CHECK_FALSE(r.converged);
    CHECK(r.residual > *o.tvqc.eps);
}

TEST_CASE("single precision: TVQC and Richardson-Lucy (cyclic and linear) within tolerance") {
    const bool sanitized = std::getenv("PINMASK_SANITIZED") != nullptr;
    const int n = sanitized ? 64 : 256;
    const Problem P = make(n, 31);
    for (DecodeMethod m : {DecodeMethod::kTvqc, DecodeMethod::kRichardsonLucy}) {
        for (ConvModel model : {ConvModel::kCyclic, ConvModel::kLinear}) {
            DecodeOptions o;
            o.method = m;
            o.model = model;
            o.tvqc.noise_sigma = 0.01 / std::sqrt(3.0);  // the uniform noise of make()
            o.tvqc.nonnegative = model == ConvModel::kLinear;
            o.iterative.max_iterations = 60;
            o.iterative.tolerance = 0.0;
            o.iterative.record_history = false;
            const Plane p = m == DecodeMethod::kRichardsonLucy ? Plane(P.p.max(0.0)) : P.p;
            const DecodeResult d = decode_plane(p, P.psf, o);
            o.single_precision = true;
            const DecodeResult s = decode_plane(p, P.psf, o);
            const int method_id = static_cast<int>(m), model_id = static_cast<int>(model);
            const double err = rel_l2(s.image, d.image);
            INFO("method " << method_id << " model " << model_id << " rel l2 " << err);
            CHECK(err <= (m == DecodeMethod::kTvqc ? kSingleTvqcTol : kSingleRlTol));
            CHECK(err > 0.0);  // it really ran in float
            CHECK(s.constraint_met == d.constraint_met);
        }
    }
}
