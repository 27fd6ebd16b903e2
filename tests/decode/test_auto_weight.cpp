// The automatic weight of the closed-form decoders (decode/solvers/auto_weight.hpp) and the noise
// estimate it reads (decode/solvers/noise_estimate.hpp), against closed forms: a white Gaussian
// scene under white noise, where the Wiener filter of least error has NSR = sigma_n^2 / sigma_x^2
// (per-pixel variances). Captures are rendered here by a direct circular sum (the deconvwnr
// centring written out), not by the decoder's FFT operator.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/auto_weight.hpp"
#include "decode/solvers/noise_estimate.hpp"
#include "tests/decode/test_decode_support.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Standard normal values by Box-Muller from a seeded 64-bit Mersenne twister (the same numbers
// on every standard library).
Plane gaussian_plane(int rows, int cols, std::uint64_t seed, double sigma) {
    std::mt19937_64 rng(seed);
    const double two_pi = 6.283185307179586;
    Plane p(rows, cols);
    for (Eigen::Index i = 0; i < p.size(); ++i) {
        const double u1 = (static_cast<double>(rng() >> 11) + 1.0) * 0x1p-53;
        const double u2 = static_cast<double>(rng() >> 11) * 0x1p-53;
        p.data()[i] = sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(two_pi * u2);
    }
    return p;
}

// Circular convolution by the direct sum, the PSF's element (pr / 2, pc / 2) at the origin.
Plane circular_blur(const Plane& x, const Plane& psf) {
    const Eigen::Index R = x.rows(), C = x.cols(), cr = psf.rows() / 2, cc = psf.cols() / 2;
    Plane out = Plane::Zero(R, C);
    for (Eigen::Index r = 0; r < psf.rows(); ++r)
        for (Eigen::Index c = 0; c < psf.cols(); ++c) {
            const double a = psf(r, c);
            if (a == 0.0) continue;
            for (Eigen::Index i = 0; i < R; ++i)
                for (Eigen::Index j = 0; j < C; ++j)
                    out(((i + r - cr) % R + R) % R, ((j + c - cc) % C + C) % C) += a * x(i, j);
        }
    return out;
}

// A pinhole array: K square spots of `spot` pixels at distinct random cells of a grid of
// `cells` x `cells` cells of `spot` pixels, sum 1.
Plane pinhole_psf(int cells, int spot, int k, unsigned seed) {
    std::mt19937 rng(seed);
    Plane a = Plane::Zero(cells * spot, cells * spot);
    std::vector<int> order(cells * cells);
    for (int i = 0; i < cells * cells; ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    for (int i = 0; i < k; ++i)
        a.block((order[i] / cells) * spot, (order[i] % cells) * spot, spot, spot).setConstant(1.0);
    return a / a.sum();
}

struct Camera {
    std::string name;
    Plane psf;
};

std::vector<Camera> cameras() {
    return {{"pinhole array 16 x 16 cells of 4 px, K = 12", pinhole_psf(16, 4, 12, 7)},
            {"pinhole array 8 x 8 cells of 3 px, K = 5", pinhole_psf(8, 3, 5, 11)},
            {"dominant-centre 7 x 7", random_psf(7, 7, 3)},
            {"5 x 5 box", Plane::Constant(5, 5, 1.0 / 25)}};
}

double mse(const Plane& a, const Plane& b) { return (a - b).square().mean(); }

DecodeResult wiener(const Plane& p, const Plane& psf, double nsr, bool automatic) {
    DecodeOptions o;
    o.method = DecodeMethod::kWiener;
    o.wiener.nsr = nsr;
    o.wiener.automatic = automatic;
    return decode_plane(p, psf, o);
}

}  // namespace

TEST_CASE("noise estimate: MAD of the diagonal Haar details recovers sigma under a smooth scene") {
    const int R = 128, C = 96;
    Plane smooth(R, C);
    for (int r = 0; r < R; ++r)
        for (int c = 0; c < C; ++c) smooth(r, c) = 50.0 + 0.3 * r + 20.0 * std::sin(c / 9.0);
    for (double sigma : {0.05, 1.0, 7.0}) {
        const double est = estimate_noise_sigma(smooth + gaussian_plane(R, C, 5, sigma));
        CAPTURE(sigma);
        // 3072 details: the MAD's relative standard error is 1.36 / sqrt(3072) = 2.5 %.
        CHECK(est == doctest::Approx(sigma).epsilon(0.08));
    }
    CHECK(estimate_noise_sigma(smooth.topLeftCorner(1, 5)) == 0.0);
    CHECK(estimate_noise_sigma(Plane::Constant(8, 8, 3.0)) == 0.0);
}

TEST_CASE("automatic Wiener NSR: white scene and noise land on sigma_n^2 / sigma_x^2") {
    // The rule with the noise sigma given (a white scene is white noise to any estimator at
    // the finest scale when the PSF barely blurs it: the estimator is tested on its own above).
    const int R = 64, C = 80;
    const double sigma_x = 1.0;
    for (const Camera& cam : cameras()) {
        for (double sigma_n : {0.02, 0.1, 0.3}) {
            CAPTURE(cam.name);
            CAPTURE(sigma_n);
            const Plane x = gaussian_plane(R, C, 21, sigma_x);
            const Plane p = circular_blur(x, cam.psf) + gaussian_plane(R, C, 22, sigma_n);
            const double optimum = sigma_n * sigma_n / (sigma_x * sigma_x);
            const ConvolutionOperator op(
                cam.psf,
                make_conv_geometry(ConvModel::kCyclic, R, C, static_cast<int>(cam.psf.rows()),
                                   static_cast<int>(cam.psf.cols())));
            const AutoWeight a =
                choose_closed_form_weight(p, op.otf(), Plane::Ones(R, C / 2 + 1), R, C, sigma_n);
            CAPTURE(a.weight);
            CAPTURE(a.alpha);
            // One realisation of 5120 pixels: the fitted variance is within a few per cent.
            CHECK(a.weight > optimum / 1.5);
            CHECK(a.weight < optimum * 1.5);
            const double loss_db =
                10 * std::log10(mse(wiener(p, cam.psf, a.weight, false).image, x) /
                                mse(wiener(p, cam.psf, optimum, false).image, x));
            CHECK(loss_db < 0.05);
        }
    }
}

TEST_CASE("automatic Wiener NSR with the noise estimated: white scene through a pinhole array") {
    // A pinhole array of 4 px spots keeps the blurred scene out of the finest scale, so the
    // estimate reads the noise; the decode lands within 0.2 dB of the optimum NSR's.
    const int R = 64, C = 80;
    const Plane psf = pinhole_psf(16, 4, 12, 7);
    for (double sigma_n : {0.1, 0.3}) {
        CAPTURE(sigma_n);
        const Plane x = gaussian_plane(R, C, 23, 1.0);
        const Plane p = circular_blur(x, psf) + gaussian_plane(R, C, 24, sigma_n);
        const DecodeResult a = wiener(p, psf, 0.0, true);
        REQUIRE(a.auto_weight.has_value());
        CHECK(a.auto_weight->noise_sigma == doctest::Approx(sigma_n).epsilon(0.15));
        const double loss_db =
            10 *
            std::log10(mse(a.image, x) / mse(wiener(p, psf, sigma_n * sigma_n, false).image, x));
        CHECK(loss_db < 0.2);
    }
}

TEST_CASE("automatic Wiener NSR with the noise sigma given is the risk rule's minimiser") {
    // With the true sigma the only estimate left is the scene spectrum's.
    const int R = 64, C = 64;
    const Plane psf = pinhole_psf(16, 4, 12, 7);
    const Plane x = gaussian_plane(R, C, 31, 2.0);
    const double sigma_n = 0.2;
    const Plane p = circular_blur(x, psf) + gaussian_plane(R, C, 32, sigma_n);
    const ComplexPlane otf = [&] {
        ConvolutionOperator op(psf, make_conv_geometry(ConvModel::kCyclic, R, C, 64, 64));
        return op.otf();
    }();
    const Plane ones = Plane::Ones(R, C / 2 + 1);
    const AutoWeight w = choose_closed_form_weight(p, otf, ones, R, C, sigma_n);
    CHECK(w.noise_sigma == sigma_n);
    CHECK(w.weight == doctest::Approx(sigma_n * sigma_n / 4.0).epsilon(0.3));
    // The risk of a white scene (S = sigma_x^2 except the mean) is least at sigma_n^2/sigma_x^2.
    Plane s = Plane::Constant(R, C / 2 + 1, 4.0);
    const double noise = sigma_n * sigma_n;
    const double r0 = closed_form_risk(otf, ones, s, noise, C, noise / 4.0);
    for (double f : {0.5, 0.9, 1.1, 2.0})
        CHECK(closed_form_risk(otf, ones, s, noise, C, f * noise / 4.0) > r0);
}

TEST_CASE("automatic weights do not depend on the capture's units (x1000, electrons, 2^k)") {
    const int R = 64, C = 64;
    const Plane psf = pinhole_psf(16, 4, 12, 7);
    Plane x(R, C);
    for (int r = 0; r < R; ++r)
        for (int c = 0; c < C; ++c) x(r, c) = 0.5 + 0.4 * std::sin(r / 5.0) * std::cos(c / 7.0);
    const Plane p = circular_blur(x, psf) + gaussian_plane(R, C, 41, 0.01);
    for (DecodeMethod method : {DecodeMethod::kWiener, DecodeMethod::kTikhonov}) {
        DecodeOptions o;
        o.method = method;
        o.wiener.automatic = true;
        o.tikhonov.automatic = true;
        const DecodeResult base = decode_plane(p, psf, o);
        REQUIRE(base.auto_weight.has_value());
        // 1000 (a thousandfold capture), 3.7 electrons per count, 1/4096 (exact).
        for (double k : {1000.0, 3.7, 1.0 / 4096}) {
            CAPTURE(k);
            const DecodeResult scaled = decode_plane(p * k, psf, o);
            REQUIRE(scaled.auto_weight.has_value());
            // The search ends on a flat minimum: rounding moves it by ~sqrt(machine epsilon).
            CHECK(scaled.auto_weight->weight ==
                  doctest::Approx(base.auto_weight->weight).epsilon(1e-6));
            CHECK(scaled.auto_weight->noise_sigma ==
                  doctest::Approx(base.auto_weight->noise_sigma * k).epsilon(1e-9));
            const double err = (scaled.image - base.image * k).abs().maxCoeff();
            CHECK(err <= 1e-6 * k * base.image.abs().maxCoeff());
            if (k == 1.0 / 4096) CHECK(scaled.auto_weight->weight == base.auto_weight->weight);
        }
    }
}

TEST_CASE(
    "automatic weight: tikhonov identity chooses Wiener's NSR; a noise-free capture a small one") {
    const int R = 48, C = 48;
    const Plane psf = pinhole_psf(8, 3, 5, 11);
    const Plane x = gaussian_plane(R, C, 51, 1.0);
    const Plane p = circular_blur(x, psf) + gaussian_plane(R, C, 52, 0.1);
    DecodeOptions o;
    o.method = DecodeMethod::kTikhonov;
    o.tikhonov.automatic = true;
    const DecodeResult t = decode_plane(p, psf, o);
    const DecodeResult w = wiener(p, psf, 0.0, true);
    REQUIRE(t.auto_weight.has_value());
    CHECK(t.auto_weight->weight == w.auto_weight->weight);
    // A ramp without noise: every diagonal detail off the wrap-around rows is 0, so sigma = 0
    // and the risk is least at the smallest weight searched (1e-10 max |H|^2, max |H| = 1).
    Plane ramp(R, C);
    for (int r = 0; r < R; ++r)
        for (int c = 0; c < C; ++c) ramp(r, c) = 1.0 + 0.01 * r + 0.02 * c;
    const DecodeResult clean = wiener(circular_blur(ramp, psf), psf, 0.0, true);
    CHECK(clean.auto_weight->noise_sigma < 1e-12);
    CHECK(clean.auto_weight->weight < 1.01e-10);
    // An explicit weight records no automatic choice.
    CHECK_FALSE(wiener(p, psf, 0.01, false).auto_weight.has_value());
}

TEST_CASE("automatic NSR excludes a per-frequency NSR map") {
    DecodeOptions o;
    o.wiener.automatic = true;
    o.wiener.nsr_per_frequency = Plane::Constant(8, 8, 0.1);
    CHECK_THROWS_AS(o.validate(), InvalidInput);
}

TEST_CASE("a given noise sigma for the automatic weights must be finite and >= 0") {
    DecodeOptions o;
    o.wiener.automatic = true;
    for (double bad : {-1.0, std::nan("")}) {
        o.auto_noise_sigma = bad;
        CHECK_THROWS_AS(o.validate(), InvalidInput);
    }
    o.auto_noise_sigma = 0.5;
    CHECK_NOTHROW(o.validate());
}

TEST_CASE("automatic TV weight: k sigma ||a||_2 min(1, (16 / SNR)^(2/3)), in capture units") {
    const int R = 48, C = 48;
    const Plane psf = pinhole_psf(12, 4, 8, 13);
    Plane x(R, C);
    for (int r = 0; r < R; ++r)
        for (int c = 0; c < C; ++c) x(r, c) = (r / 12 + c / 16) % 2 ? 1.0 : 0.2;
    const Plane p = circular_blur(x, psf) + gaussian_plane(R, C, 61, 0.02);
    DecodeOptions o;
    o.method = DecodeMethod::kTv;
    o.tv.automatic = true;
    o.iterative.max_iterations = 20;
    const DecodeResult a = decode_plane(p, psf, o);
    REQUIRE(a.auto_weight.has_value());
    const double sigma = estimate_noise_sigma(p);
    CHECK(a.auto_weight->noise_sigma == sigma);
    // The rule written out: this capture's SNR (mean / sigma, about 30) is above the knee.
    const double norm = std::sqrt(psf.square().sum()), snr = p.mean() / sigma;
    REQUIRE(snr > 16.0);
    CHECK(a.auto_weight->weight ==
          doctest::Approx(2.4 * sigma * norm * std::pow(16.0 / snr, 2.0 / 3.0)).epsilon(1e-12));
    // Below the knee, and for a signed capture (mean <= 0), the factor is 1; a given sigma is
    // used as it is.
    const Plane noisy = circular_blur(x, psf) + gaussian_plane(R, C, 62, 0.2);
    const double s_noisy = estimate_noise_sigma(noisy);
    REQUIRE(noisy.mean() / s_noisy < 16.0);
    CHECK(choose_tv_weight(noisy, psf).weight ==
          doctest::Approx(2.4 * s_noisy * norm).epsilon(1e-12));
    const Plane centred = p - p.mean() - 0.1;
    CHECK(choose_tv_weight(centred, psf, 0.05).weight ==
          doctest::Approx(2.4 * 0.05 * norm).epsilon(1e-12));
    CHECK(choose_tv_weight(p, psf, 0.002).weight ==
          doctest::Approx(2.4 * 0.002 * norm * std::pow(16.0 * 0.002 / p.mean(), 2.0 / 3.0))
              .epsilon(1e-12));
    // The rule is proportional to sigma ||a||_2: a PSF scaled by 4 and a capture scaled by 8
    // scale it by 4 and 8 (powers of two: exact).
    CHECK(choose_tv_weight(p, psf * 4.0).weight == 4.0 * a.auto_weight->weight);
    CHECK(choose_tv_weight(p * 8.0, psf).weight == 8.0 * a.auto_weight->weight);
    const DecodeResult k = decode_plane(p * 1000.0, psf, o);
    CHECK(k.auto_weight->weight == doctest::Approx(1000.0 * a.auto_weight->weight).epsilon(1e-12));
    CHECK((k.image - a.image * 1000.0).abs().maxCoeff() <=
          1e-6 * 1000.0 * a.image.abs().maxCoeff());
    CHECK(a.warnings.empty());
}

TEST_CASE(
    "warnings: a TV weight 10x from the automatic one; a closed form on a full linear frame") {
    const int R = 48, C = 48;
    const Plane psf = pinhole_psf(12, 4, 8, 13);
    const Plane x = random_plane(R + 47, C + 47, 71, 0.5, 1.0);
    const Plane p = circular_blur(x, psf).block(0, 0, R, C) + gaussian_plane(R, C, 72, 0.02);
    const double automatic = choose_tv_weight(p, psf).weight;
    DecodeOptions o;
    o.method = DecodeMethod::kTv;
    o.iterative.max_iterations = 2;
    for (double f : {11.0, 1.0 / 11, 9.0, 1.0 / 9}) {
        CAPTURE(f);
        o.tv.lambda = f * automatic;
        const DecodeResult r = decode_plane(p, psf, o);
        if (f > 10 || f < 0.1) {
            REQUIRE(r.warnings.size() == 1);
            CHECK(r.warnings[0].find("`lambda` auto") != std::string::npos);
        } else {
            CHECK(r.warnings.empty());
        }
    }
    // The linear model: a capture lit to its edges warns for wiener, a dark border does not,
    // and the cyclic model never does (no border).
    DecodeOptions w;
    w.model = ConvModel::kLinear;
    const DecodeResult full = decode_plane(p, psf, w);
    REQUIRE(full.warnings.size() == 1);
    CHECK(full.warnings[0].find("`method` tv") != std::string::npos);
    Plane dark = Plane::Zero(R, C);
    dark.block(16, 16, 16, 16) = p.block(16, 16, 16, 16);
    CHECK(decode_plane(dark, psf, w).warnings.empty());
    w.model = ConvModel::kCyclic;
    CHECK(decode_plane(p, psf, w).warnings.empty());
}
