#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/errors/error.hpp"
#include "decode/capture/capture.hpp"
#include "decode/capture/decoder.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/psf.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"
#include "tests/support/close.hpp"
#include "tests/support/direct_cyclic.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::direct_cyclic;
using pinmask::test::random_plane;

namespace {

// FFT convolution against the direct sum: rounding of O(log N) FFT stages on values <= 1.
constexpr double kConvolutionTol = 1e-12;
// z-score bound for the statistical checks below: a correct sampler fails one check with
// probability ~6e-7 (two-sided normal tail at 5 standard errors); the draws are seeded, so a
// pass is reproducible.
constexpr double kZ = 5.0;

// Connected components (4-neighbourhood, not wrapping) of the pixels above `threshold`.
int count_spots(const Plane& img, double threshold) {
    const int R = static_cast<int>(img.rows()), C = static_cast<int>(img.cols());
    std::vector<int> label(static_cast<std::size_t>(R) * C, 0);
    int spots = 0;
    for (int r0 = 0; r0 < R; ++r0) {
        for (int c0 = 0; c0 < C; ++c0) {
            if (!(img(r0, c0) > threshold) || label[r0 * C + c0]) continue;
            ++spots;
            std::vector<std::pair<int, int>> stack{{r0, c0}};
            label[r0 * C + c0] = spots;
            while (!stack.empty()) {
                const auto [r, c] = stack.back();
                stack.pop_back();
                const int nb[4][2] = {{r - 1, c}, {r + 1, c}, {r, c - 1}, {r, c + 1}};
                for (const auto& q : nb) {
                    if (q[0] < 0 || q[0] >= R || q[1] < 0 || q[1] >= C) continue;
                    if (img(q[0], q[1]) > threshold && !label[q[0] * C + q[1]]) {
                        label[q[0] * C + q[1]] = spots;
                        stack.push_back({q[0], q[1]});
                    }
                }
            }
        }
    }
    return spots;
}

// The paper's geometry (n = 16, K = 20) with an exact 8 x 8 box kernel at 8 pixels per cell:
// every pinhole lights exactly its own 8 x 8 cell.
Plane paper_box_psf() {
    std::mt19937_64 rng(1);
    const Pattern p = paper_pattern(rng);
    return synthesize_psf(p, measured_kernel(Plane::Ones(8, 8), 8, "box 8 x 8"), 8);
}

NoiseModel photon_model(double ppp) {
    NoiseModel m;
    m.kind = NoiseKind::kPhoton;
    m.photons_per_pinhole = ppp;
    return m;
}

}  // namespace

TEST_CASE("cyclic capture equals the direct circular sum with the decoder's centring") {
    for (const auto& size : {std::pair{7, 7}, {13, 11}, {16, 16}, {5, 8}}) {
        const int rows = size.first, cols = size.second;
        CAPTURE(rows);
        CAPTURE(cols);
        const Plane x = random_plane(rows, cols, 3);
        Plane a = random_plane(rows, cols, 4).square().square();  // uneven, all positive
        a /= a.sum();
        const Plane c = cyclic_capture(x, a);
        CHECK(test::max_rel_error(c, direct_cyclic(x, a)) < kConvolutionTol);
    }
}

TEST_CASE("a point scene at the centre reproduces the PSF (no shift)") {
    const Plane a = paper_box_psf();
    const Plane c = cyclic_capture(point_scene(128, 128), a);
    CHECK(test::max_rel_error(c, a) < kConvolutionTol);
    CHECK(c.minCoeff() >= 0.0);  // rounding below zero is clipped for non-negative inputs
}

TEST_CASE("tiling: periodic extension whose centred crop is the period") {
    for (const auto& sizes :
         {std::array{7, 5, 30, 17}, {16, 16, 48, 40}, {13, 11, 13, 11}, {8, 8, 5, 20}}) {
        const int pr = sizes[0], pc = sizes[1], R = sizes[2], C = sizes[3];
        CAPTURE(pr);
        CAPTURE(R);
        const Plane period = random_plane(pr, pc, 9);
        const TileOrigin o = centred_tile_origin(R, C, pr, pc);
        const Plane frame = tile_period(period, R, C, o);
        for (int r = 0; r < R; ++r)
            for (int c = 0; c < C; ++c) {
                if (r + pr < R) REQUIRE(frame(r + pr, c) == frame(r, c));
                if (c + pc < C) REQUIRE(frame(r, c + pc) == frame(r, c));
            }
        if (R >= pr && C >= pc) {
            const CropWindow w = crop_window(R, C, pr, pc, CropSpec{});
            CHECK((crop(Image(frame), w).channels[0] == period).all());
        }
    }
}

TEST_CASE("noiseless capture + Wiener with a tiny NSR recovers the scene (PSNR > 60 dB)") {
    // A random-family mask with a one-pixel kernel (the small-pinhole limit): A^ = P^(k mod n) / K
    // has no zeros when the pattern spectrum has none, checked first. Physical kernels are
    // low-pass (an even-width symmetric kernel is exactly 0 at Nyquist), so they would test the
    // kernel, not the forward model. With min |A^|^2 far above deconvwnr's floor (1.5e-8) and
    // NSR 1e-12 the filter is the exact inverse up to NSR / |A^|^2 and rounding. Sizes: even
    // (n 16, ppc 8: the paper's 128) and odd/prime (n 11, ppc 7: 77).
    for (const auto& setup : {std::array{16, 8, 20}, {11, 7, 9}}) {
        const int n = setup[0], ppc = setup[1], holes = setup[2];
        CAPTURE(n);
        std::mt19937_64 rng(1);
        RandomSparseOptions r;
        r.n = n;
        r.holes = holes;
        const Pattern p = random_sparse_pattern(r, rng);
        const double min_abs_p = pattern_spectrum(p).abs().minCoeff();
        INFO("min |P^| = " << min_abs_p);
        REQUIRE(min_abs_p / holes > 1e-2);
        const Plane psf = synthesize_psf(p, measured_kernel(Plane::Ones(1, 1), ppc, "delta"), ppc);
        const int m = n * ppc;
        for (const char* name : {"usaf", "natural"}) {
            const Image scene = make_scene(scene_from_name(name), m, m);
            SimulationOptions o;
            o.noise.kind = NoiseKind::kNone;
            const SimulatedCapture s = simulate_capture(scene, psf, holes, n * n, o);
            DecodeOptions d;
            d.wiener.nsr = 1e-12;
            const Plane x = decode_plane(s.capture.channels[0], psf, d).image;
            CHECK(psnr_db(x, scene.channels[0]) > 60.0);
        }
    }
}

TEST_CASE("point scene on a 2 x 2-period sensor: one spot per pinhole per tile (80)") {
    const Plane a = paper_box_psf();
    SimulationOptions o;
    o.noise.kind = NoiseKind::kNone;
    o.full_sensor = true;
    o.sensor_rows = 256;
    o.sensor_cols = 256;
    const SimulatedCapture s = simulate_capture(Image(point_scene(128, 128)), a, 20, 256, o);
    const Plane& f = s.capture.channels[0];
    REQUIRE(f.rows() == 256);
    REQUIRE(f.cols() == 256);
    // Box spots are exactly 8 x 8 pixels of value 1 / (20 * 64), the rest 0 up to rounding.
    CHECK(count_spots(f, 0.5 * f.maxCoeff()) == 80);
    CHECK((f > 0.5 * f.maxCoeff()).count() == 80 * 64);
    CHECK(f.maxCoeff() == doctest::Approx(1.0 / (20.0 * 64.0)).epsilon(1e-12));
}

TEST_CASE("same seed, same capture; another seed, another; the dark frame is its own stream") {
    const Plane a = paper_box_psf();
    const Image scene = make_scene(scene_from_name("letter-R"), 128, 128);
    SimulationOptions o;
    o.noise = photon_model(500.0);
    o.noise.read_noise_e = 3.0;
    o.noise.dark_current_e = 5.0;
    o.noise.film_optical_density = 2.0;
    const SimulatedCapture s1 = simulate_capture(scene, a, 20, 256, o);
    const SimulatedCapture s2 = simulate_capture(scene, a, 20, 256, o);
    CHECK((s1.capture.channels[0] == s2.capture.channels[0]).all());
    o.dark_frame = true;
    const SimulatedCapture s3 = simulate_capture(scene, a, 20, 256, o);
    CHECK((s1.capture.channels[0] == s3.capture.channels[0]).all());
    o.seed = 2;
    const SimulatedCapture s4 = simulate_capture(scene, a, 20, 256, o);
    CHECK((s4.capture.channels[0] != s1.capture.channels[0]).count() > 1000);
    CHECK((s4.dark.channels[0] != s3.dark.channels[0]).count() > 1000);
}

TEST_CASE("Gaussian noise: the empirical SNR matches the requested SNR") {
    const Plane a = paper_box_psf();
    const Image scene = make_scene(scene_from_name("natural"), 128, 128);
    for (double snr : {10.0, 30.0}) {
        SimulationOptions o;
        o.noise.kind = NoiseKind::kGaussianSnr;
        o.noise.snr_db = snr;
        const SimulatedCapture s = simulate_capture(scene, a, 20, 256, o);
        const Plane noise = s.capture.channels[0] - s.clean.channels[0];
        const double n = static_cast<double>(noise.size());
        const double empirical =
            10.0 * std::log10(s.clean.channels[0].square().mean() / noise.square().mean());
        // mean(noise^2) / sigma^2 has relative standard deviation sqrt(2 / N); in dB that is
        // 10 / ln(10) sqrt(2 / N).
        const double tol_db = kZ * 10.0 / std::log(10.0) * std::sqrt(2.0 / n);
        CHECK(std::fabs(empirical - snr) < tol_db);
    }
}

TEST_CASE("photon noise on a uniform scene: Poisson mean and variance") {
    // Uniform scene v: every pixel's electrons are Poisson(ppp K v), the capture e / (ppp K):
    // mean v, variance v / (ppp K).
    const Plane a = paper_box_psf();
    const double v = 0.6, ppp = 50.0, K = 20.0;
    SimulationOptions o;
    o.noise = photon_model(ppp);
    const SimulatedCapture s = simulate_capture(Image(Plane::Constant(128, 128, v)), a, 20, 256, o);
    const Plane& c = s.capture.channels[0];
    const double n = static_cast<double>(c.size());
    const double var_expected = v / (ppp * K);
    const double mean = c.mean();
    const double var = (c - mean).square().sum() / (n - 1.0);
    CHECK(std::fabs(mean - v) < kZ * std::sqrt(var_expected / n));
    // Sample variance: standard error var sqrt(2 / (N - 1)) (Poisson at mean 600 is near
    // normal; its excess kurtosis 1/600 adds < 0.1 %).
    CHECK(std::fabs(var - var_expected) < kZ * var_expected * std::sqrt(2.0 / (n - 1.0)));
    // The electron counts are integers: the capture times ppp K is integral.
    const Plane e = c * (ppp * K);
    CHECK(((e - e.round()).abs() < 1e-6).all());
}

TEST_CASE("film leakage and dark current: background in the capture, dark frame mean") {
    const Plane a = paper_box_psf();
    const Image scene = make_scene(scene_from_name("usaf"), 128, 128);
    const double ppp = 200.0, K = 20.0, cells = 256.0, od = 1.5, dark_e = 8.0, read_e = 2.0;
    SimulationOptions o;
    o.noise = photon_model(ppp);
    o.noise.film_optical_density = od;
    o.noise.dark_current_e = dark_e;
    o.noise.read_noise_e = read_e;
    o.dark_frame = true;
    const SimulatedCapture s = simulate_capture(scene, a, 20, 256, o);
    // Leak: ppp 10^-OD over the (n^2 - K) closed cells, times the capture mean (= scene mean).
    const double leak_e = ppp * std::pow(10.0, -od) * (cells - K) * s.clean.channels[0].mean();
    const double offset = (leak_e + dark_e) / (ppp * K);  // normalised units
    CHECK(s.background[0] == doctest::Approx(offset).epsilon(1e-12));
    const Plane& dark = s.dark.channels[0];
    const double n = static_cast<double>(dark.size());
    const double dark_sd = std::sqrt(leak_e + dark_e + read_e * read_e) / (ppp * K);
    CHECK(std::fabs(dark.mean() - offset) < kZ * dark_sd / std::sqrt(n));
    const double dark_var = (dark - dark.mean()).square().sum() / (n - 1.0);
    CHECK(std::fabs(std::sqrt(dark_var) - dark_sd) < kZ * dark_sd / std::sqrt(2.0 * (n - 1.0)));
    // The capture carries signal + background: capture - dark has the clean capture's mean.
    const Plane diff = s.capture.channels[0] - dark;
    const double diff_sd =
        std::sqrt(std::pow(dark_sd, 2) * 2.0 + s.clean.channels[0].mean() / (ppp * K));
    CHECK(std::fabs(diff.mean() - s.clean.channels[0].mean()) < kZ * diff_sd / std::sqrt(n));
    CHECK(s.capture.channels[0].mean() > s.clean.channels[0].mean() + 0.5 * offset);
}

TEST_CASE("validation: the dark frame needs the photon model; sizes must match") {
    const Plane a = paper_box_psf();
    SimulationOptions o;
    o.noise.kind = NoiseKind::kGaussianSnr;
    o.dark_frame = true;
    CHECK_THROWS_AS(o.validate(), InvalidInput);
    o.dark_frame = false;
    o.full_sensor = true;
    o.sensor_rows = 0;
    CHECK_THROWS_AS(o.validate(), InvalidInput);
    CHECK_THROWS_AS(cyclic_capture(Plane::Zero(64, 64), a), InvalidInput);
    CHECK_THROWS_AS(cyclic_capture(Plane::Zero(128, 128), Plane::Zero(128, 128)), InvalidInput);
}
