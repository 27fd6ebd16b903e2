// The robust (fabrication-error) score: parsing and validation of --robust, the jitter
// statistics against a brute-force integral, the closed-form expected MSE against a Monte Carlo
// of the same errors (fabricated PSFs drawn by tests/research/fabricated_sample, decoded with
// the nominal filter), zero errors giving exactly the nominal score, and deterministic draws.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/optics/camera.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/robust_sample.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/simulate/scene_prior.hpp"
#include "optimize/simulate/scenes.hpp"
#include "tests/research/expected_psf_decoder.hpp"
#include "tests/research/fabricated_sample.hpp"
#include "tests/support/random_pattern.hpp"

namespace pinmask {
namespace {

std::string message_of(const std::string& spec) {
    try {
        parse_fabrication_errors(spec);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

ComplexPlane full_fft(const Plane& x) {
    return FftC2(static_cast<int>(x.rows()), static_cast<int>(x.cols()))
        .forward(x.cast<std::complex<double>>());
}

}  // namespace

TEST_CASE("--robust parses any subset of keys with length units") {
    const FabricationErrors e = parse_fabrication_errors("size=5um,jitter=2um,missing=0.01");
    CHECK(e.size_bias_m == doctest::Approx(5e-6).epsilon(1e-12));
    CHECK(e.jitter_m == doctest::Approx(2e-6).epsilon(1e-12));
    CHECK(e.missing == doctest::Approx(0.01).epsilon(1e-12));
    const FabricationErrors j = parse_fabrication_errors("jitter=0.002mm");
    CHECK(j.jitter_m == doctest::Approx(2e-6).epsilon(1e-12));
    CHECK(j.size_bias_m == 0.0);
    CHECK(j.missing == 0.0);
    CHECK(parse_fabrication_errors("size=440nm").size_bias_m ==
          doctest::Approx(4.4e-7).epsilon(1e-12));
    CHECK(!parse_fabrication_errors("missing=0").any());
}

TEST_CASE("hostile --robust values are refused naming the key") {
    CHECK(message_of("size=-5um").find("`robust` size") != std::string::npos);
    CHECK(message_of("jitter=nan").find("`robust` jitter") != std::string::npos);
    CHECK(message_of("missing=1").find("`robust` missing") != std::string::npos);
    CHECK(message_of("missing=-0.1").find("`robust` missing") != std::string::npos);
    CHECK(message_of("missing=inf").find("`robust` missing") != std::string::npos);
    CHECK(message_of("color=3").find("'color'") != std::string::npos);
    CHECK(message_of("size=5um,size=6um").find("`robust` size") != std::string::npos);
    CHECK(message_of("size=5um,size=6um").find("twice") != std::string::npos);
    CHECK(message_of("size").find("`robust`") != std::string::npos);
    CHECK(message_of("size=5um,").find("`robust`") != std::string::npos);
    CHECK(message_of("").find("`robust`") != std::string::npos);
    CHECK(message_of("size=5parsec").find("`robust` size") != std::string::npos);
    // Against the mask's pinhole side d = 440 um: jitter above one cell, bias >= d.
    const Mask m = test::random_paper_mask(8, 5, 1);
    FabricationErrors big;
    big.jitter_m = 441e-6;
    CHECK_THROWS_WITH_AS(FabricationSampler(m, big), doctest::Contains("`robust` jitter"),
                         InvalidInput);
    FabricationErrors huge;
    huge.size_bias_m = 440e-6;
    CHECK_THROWS_WITH_AS(fabricated_kernels(m, huge), doctest::Contains("`robust` size"),
                         InvalidInput);
    // A kernel that does not depend on the side cannot model a size bias.
    const Mask paper = test::random_paper_mask(8, 5, 1, "paper-fig3b");
    FabricationErrors bias;
    bias.size_bias_m = 10e-6;
    CHECK_THROWS_WITH_AS(fabricated_kernels(paper, bias), doctest::Contains("`robust` size"),
                         InvalidInput);
}

TEST_CASE("jitter statistics match a brute-force integral") {
    // Reference: midpoint sum over +-10 sigma with 400000 points of the same t(delta, theta)
    // written directly. Tolerance: the midpoint rule's error at this density is below 1e-9.
    constexpr double kTolerance = 1e-8;
    const int m = 24;
    for (const double sigma : {0.04, 0.7, 2.5}) {
        const JitterTransfer jt = jitter_transfer(sigma, m);
        const int points = 400000;
        const double lo = -10 * sigma, h = 20 * sigma / points;
        for (const int k : {0, 1, 5, 12, 19}) {
            const double theta = 2 * std::acos(-1.0) * k / m;
            std::complex<double> mean = 0.0;
            double power = 0.0, total = 0.0;
            for (int i = 0; i < points; ++i) {
                const double x = lo + (i + 0.5) * h;
                const double w = std::exp(-0.5 * x * x / (sigma * sigma));
                const double s = std::floor(x), f = x - s;
                const std::complex<double> t =
                    std::exp(std::complex<double>(0, -theta * s)) *
                    (1 - f + f * std::exp(std::complex<double>(0, -theta)));
                mean += w * t;
                power += w * std::norm(t);
                total += w;
            }
            CAPTURE(sigma);
            CAPTURE(k);
            CHECK(std::abs(jt.mean[k] - mean / total) < kTolerance);
            CHECK(std::abs(jt.power[k] - power / total) < kTolerance);
        }
    }
    const JitterTransfer none = jitter_transfer(0.0, 5);
    for (int k = 0; k < 5; ++k) CHECK(none.mean[k] == std::complex<double>(1.0, 0.0));
    CHECK_THROWS_AS(jitter_transfer(-1.0, 5), InvalidInput);
}

TEST_CASE("the closed-form robust MSE matches a Monte Carlo of fabricated PSFs") {
    // Each draw: a fabricated PSF (FabricationSampler), its exact transfer function T by FFT, and
    // the analytic MSE given T with the nominal filter G:
    //   (1/N^2) sum_k |G T - 1|^2 S + |G|^2 N sigma^2.
    // The closed form is their expectation; the tolerance is kStandardErrors standard errors
    // of the sample mean (plus 1e-12 relative for rounding).
    constexpr double kStandardErrors = 4.0;
    constexpr int kDraws = 3000;
    const Mask mask = test::random_paper_mask(8, 6, 3);
    const int m = 64;
    const ScenePrior prior = natural_scene_prior(m, m, 4, 1000, 1.0);
    NoiseModel noise;
    noise.snr_db = 25.0;
    struct Case {
        const char* name;
        FabricationErrors e;
    };
    FabricationErrors size, jitter, missing, all;
    size.size_bias_m = 60e-6;
    jitter.jitter_m = 30e-6;
    missing.missing = 0.1;
    all = {44e-6, 40e-6, 0.05};
    const Case cases[] = {{"size", size}, {"jitter", jitter}, {"missing", missing}, {"all", all}};
    const ComplexPlane p = pattern_spectrum(mask.pattern);
    const ComplexPlane h = full_fft(mask_psf(mask));
    for (const Case& c : cases) {
        const RobustWienerModel model(mask, c.e, prior, noise);
        for (const WienerFilterSpec f : {WienerFilterSpec{WienerFilterKind::kFixedNsr, 0.02},
                                         WienerFilterSpec{WienerFilterKind::kOptimal, 0.0}}) {
            const RobustError closed = model.evaluate(p, f);
            const double sigma2 = closed.nominal.noise_variance;
            const double big_n = static_cast<double>(m) * m;
            ComplexPlane g(m, m);
            for (Eigen::Index i = 0; i < g.size(); ++i) {
                const std::complex<double> hk = h.data()[i];
                const double s = prior.power.data()[i];
                const double w = f.kind == WienerFilterKind::kFixedNsr
                                     ? 1.0 / (std::norm(hk) + f.nsr)
                                     : s / (std::norm(hk) * s + big_n * sigma2);
                g.data()[i] = std::conj(hk) * w;
            }
            const FabricationSampler sampler(mask, c.e);
            double sum = 0.0, sum_sq = 0.0;
            for (int d = 0; d < kDraws; ++d) {
                std::mt19937_64 rng(static_cast<std::uint64_t>(d) + 17);
                const ComplexPlane t = full_fft(sampler.draw(rng));
                double e = 0.0;
                for (Eigen::Index i = 0; i < t.size(); ++i) {
                    const std::complex<double> gi = g.data()[i];
                    e += std::norm(gi * t.data()[i] - 1.0) * prior.power.data()[i] +
                         std::norm(gi) * big_n * sigma2;
                }
                e /= big_n * big_n;
                sum += e;
                sum_sq += e * e;
            }
            const double mean = sum / kDraws;
            const double se = std::sqrt(std::max(0.0, sum_sq / kDraws - mean * mean) / kDraws);
            CAPTURE(c.name);
            CAPTURE(f.kind == WienerFilterKind::kOptimal);
            CAPTURE(closed.mse);
            CAPTURE(mean);
            CAPTURE(se);
            CHECK(std::abs(closed.mse - mean) <= kStandardErrors * se + 1e-12 * mean);
            CHECK(closed.mse > closed.nominal.mse);  // errors always cost something here
        }
    }
}

TEST_CASE("decoder variants (expected PSF, robust filter): closed form against a Monte Carlo") {
    // As above, with the filters of the decoder variants built by the model
    // (filter_response, robust_filter_response) and checked twice: their expected fabricated
    // MSE against the Monte Carlo of fabricated PSFs, and their nominal MSE against the same
    // sum with the exact nominal transfer function (no sampling: kRelTolerance).
    constexpr double kStandardErrors = 4.0;
    constexpr double kRelTolerance = 1e-9;
    constexpr int kDraws = 3000;
    const Mask mask = test::random_paper_mask(8, 6, 3);
    const int m = 64;
    const ScenePrior prior = natural_scene_prior(m, m, 4, 1000, 1.0);
    NoiseModel noise;
    noise.snr_db = 25.0;
    const FabricationErrors e{60e-6, 30e-6, 0.05};
    const ComplexPlane p = pattern_spectrum(mask.pattern);
    const ComplexPlane h = full_fft(mask_psf(mask));
    const RobustWienerModel model(mask, e, prior, noise);
    const double big_n = static_cast<double>(m) * m;
    const auto mse_given = [&](const ComplexPlane& g, const ComplexPlane& t, double sigma2) {
        double sum = 0.0;
        for (Eigen::Index i = 0; i < t.size(); ++i) {
            sum += std::norm(g.data()[i] * t.data()[i] - 1.0) * prior.power.data()[i] +
                   std::norm(g.data()[i]) * big_n * sigma2;
        }
        return sum / (big_n * big_n);
    };
    // The nominal-PSF fixed-NSR response is the test's own conj(H) / (|H|^2 + nsr) (frame check).
    const ComplexPlane g0 = model.filter_response(p, {WienerFilterKind::kFixedNsr, 0.02});
    double frame_error = 0.0;
    for (Eigen::Index i = 0; i < h.size(); ++i) {
        const std::complex<double> hk = h.data()[i];
        frame_error =
            std::max(frame_error, std::abs(g0.data()[i] - std::conj(hk) / (std::norm(hk) + 0.02)));
    }
    CHECK(frame_error <= 1e-9);

    struct Variant {
        const char* name;
        RobustError closed;
        ComplexPlane g;
    };
    const WienerFilterSpec fixed{WienerFilterKind::kFixedNsr, 0.02};
    const WienerFilterSpec optimal{WienerFilterKind::kOptimal, 0.0};
    const std::vector<Variant> variants{
        {"expected PSF, fixed NSR", evaluate_expected_psf(model, p, fixed),
         expected_psf_filter_response(model, p, fixed)},
        {"expected PSF, optimal", evaluate_expected_psf(model, p, optimal),
         expected_psf_filter_response(model, p, optimal)},
        {"expected PSF, tuned NSR", evaluate_expected_psf_tuned_nsr(model, p),
         expected_psf_filter_response(model, p, {WienerFilterKind::kTunedNsr, 0.0})},
        {"robust filter", model.evaluate_robust_filter(p), model.robust_filter_response(p)},
        {"nominal PSF, optimal", model.evaluate(p, optimal), model.filter_response(p, optimal)}};
    const FabricationSampler sampler(mask, e);
    for (const Variant& v : variants) {
        const double sigma2 = v.closed.nominal.noise_variance;
        double sum = 0.0, sum_sq = 0.0;
        for (int d = 0; d < kDraws; ++d) {
            std::mt19937_64 rng(static_cast<std::uint64_t>(d) + 17);
            const double x = mse_given(v.g, full_fft(sampler.draw(rng)), sigma2);
            sum += x;
            sum_sq += x * x;
        }
        const double mean = sum / kDraws;
        const double se = std::sqrt(std::max(0.0, sum_sq / kDraws - mean * mean) / kDraws);
        const double nominal = mse_given(v.g, h, sigma2);
        CAPTURE(v.name);
        CAPTURE(v.closed.mse);
        CAPTURE(mean);
        CAPTURE(se);
        CHECK(std::abs(v.closed.mse - mean) <= kStandardErrors * se + 1e-12 * mean);
        CHECK(std::abs(v.closed.nominal.mse - nominal) <= kRelTolerance * nominal);
    }
    // The robust filter is the best of them on the fabricated masks (its defining property),
    // and the floor is below all.
    for (const Variant& v : variants) {
        CHECK(variants[3].closed.mse <= v.closed.mse * (1.0 + kRelTolerance));
        CHECK(model.pattern_independent_floor_mse() <= v.closed.mse);
    }
}

TEST_CASE("zero errors give exactly the nominal score; tiny errors approach it") {
    const Mask mask = test::random_paper_mask(11, 7, 5);
    const int m = 88;
    const ScenePrior prior = natural_scene_prior(m, m, 3, 1000, 1.0);
    const ComplexPlane p = pattern_spectrum(mask.pattern);
    NoiseModel noise;
    const RobustWienerModel zero(mask, FabricationErrors{}, prior, noise);
    const AnalyticWienerModel nominal(
        expand_half_spectrum(kernel_spectrum(mask_kernel(mask), 11, 8), m), prior, noise);
    for (const WienerFilterSpec f : {WienerFilterSpec{WienerFilterKind::kFixedNsr, 0.01},
                                     WienerFilterSpec{WienerFilterKind::kOptimal, 0.0}}) {
        const RobustError r = zero.evaluate(p, f);
        CHECK(r.psnr_db == nominal.evaluate(p, f).psnr_db);
        CHECK(r.mse == r.nominal.mse);
        CHECK(r.loss_db() == 0.0);
        // The closed-form path itself: a 1e-17 m jitter (2e-13 px) changes the MSE by less than
        // kTiny relative. (Area resampling blurs to first order in sigma: J and B differ from 1
        // by about sigma sqrt(2/pi) (1 - cos theta), here 1e-13, amplified by at most 1/nsr.)
        constexpr double kTiny = 1e-10;
        const RobustWienerModel tiny(mask, FabricationErrors{0.0, 1e-17, 0.0}, prior, noise);
        const RobustError t = tiny.evaluate(p, f);
        CHECK(std::abs(t.mse - r.mse) <= kTiny * r.mse);
    }
    CHECK(zero.evaluate_tuned_nsr(p).psnr_db == nominal.evaluate_tuned_nsr(p).psnr_db);
    // The tuned filter (search's default under --photons) through evaluate(): the tuned NSR's
    // robust figure, not the optimal filter's.
    const RobustWienerModel some(mask, FabricationErrors{0.0, 2e-6, 0.01}, prior, noise);
    const WienerFilterSpec tuned{WienerFilterKind::kTunedNsr, 0.0};
    CHECK(some.evaluate(p, tuned).mse == some.evaluate_tuned_nsr(p).mse);
    CHECK(some.evaluate(p, tuned).mse != some.evaluate(p, {WienerFilterKind::kOptimal, 0.0}).mse);
    CHECK(zero.evaluate(p, tuned).psnr_db == nominal.evaluate_tuned_nsr(p).psnr_db);
}

TEST_CASE("fabricated PSFs: deterministic for a seed, sum about 1, nominal without errors") {
    const Mask mask = test::random_paper_mask(8, 6, 9);
    const FabricationSampler none(mask, FabricationErrors{});
    std::mt19937_64 rng(1);
    const Plane nominal = mask_psf(mask);
    // Without errors the draw is the nominal PSF up to summation order.
    CHECK((none.draw(rng) - nominal).abs().maxCoeff() < 1e-15);
    const FabricationSampler some(mask, FabricationErrors{20e-6, 5e-6, 0.0});
    std::mt19937_64 a(42), b(42);
    const Plane pa = some.draw(a), pb = some.draw(b);
    CHECK((pa - pb).abs().maxCoeff() == 0.0);
    CHECK(pa.sum() == doctest::Approx(1.0).epsilon(1e-12));
    CHECK((pa - nominal).abs().maxCoeff() > 0.0);
}

TEST_CASE(
    "simulated quality with a frequency response: bad inputs refused; the Wiener path equal") {
    constexpr double kDbTolerance = 1e-9;  // two FFT paths of the same filter
    const Mask mask = test::random_paper_mask(8, 6, 9);
    const int m = 64;
    const FabricationErrors e{20e-6, 5e-6, 0.0};
    NoiseModel noise;
    noise.snr_db = 40.0;
    SceneSpec spec;
    spec.kind = SceneKind::kNatural;
    spec.seed = 7001;
    const std::vector<NamedScene> scenes{{"natural", make_scene(spec, m, m)}};
    const RobustWienerModel model(mask, e, natural_scene_prior(m, m, 4, 1000, 1.0), noise);
    const ComplexPlane p = pattern_spectrum(mask.pattern);
    const ComplexPlane g = model.filter_response(p, {WienerFilterKind::kFixedNsr, 0.01});
    // The fixed-NSR response decodes as decode's Wiener filter of the nominal PSF does.
    const FabricatedQuality a = fabricated_filter_quality(mask, e, scenes, noise, g, 3, 5);
    const FabricatedQuality b = fabricated_wiener_quality(mask, e, scenes, noise, 0.01, 3, 5);
    CHECK(std::abs(a.nominal_psnr_db - b.nominal_psnr_db) <= kDbTolerance);
    CHECK(std::abs(a.fabricated_psnr_db - b.fabricated_psnr_db) <= kDbTolerance);
    CHECK_THROWS_AS(fabricated_filter_quality(mask, e, scenes, noise, ComplexPlane(m / 2, m), 3, 5),
                    InvalidInput);
    CHECK_THROWS_AS(fabricated_filter_quality(mask, e, scenes, noise, g, 0, 5), InvalidInput);
    CHECK_THROWS_AS(fabricated_filter_quality(mask, e, {}, noise, g, 3, 5), InvalidInput);
    CHECK_THROWS_AS(model.filter_response(p, {WienerFilterKind::kFixedNsr, -1.0}), InvalidInput);
    CHECK_THROWS_AS(model.filter_response(p, {WienerFilterKind::kFixedNsr, NAN}), InvalidInput);
    // The building blocks of other decoders: a decoder OTF off the period, a tuned NSR (it
    // depends on the decoder), crosses and variances that do not pair up are refused.
    const WienerFilterSpec fixed{WienerFilterKind::kFixedNsr, 0.01};
    CHECK_THROWS_AS(model.filter_response(p, fixed, ComplexPlane(m / 2, m)), InvalidInput);
    CHECK_THROWS_AS(
        model.filter_response(p, {WienerFilterKind::kTunedNsr, 0.0}, model.expected_transfer()),
        InvalidInput);
    const Plane power = model.kernel_otf().abs2();
    const std::vector<ComplexPlane> cross{model.kernel_otf().abs2().cast<std::complex<double>>()};
    // With the nominal kernel as decoder and as the one true transfer (cross |kappa|^2, no
    // variance) it is the nominal analytic error (optimize/metrics/analytic_error, another code
    // path).
    const AnalyticError nominal = model.nominal().evaluate(p, fixed);
    CHECK(model.mismatch_mse(p, nominal.noise_variance, fixed, power, cross, {}) ==
          doctest::Approx(nominal.mse).epsilon(1e-9));
    CHECK_THROWS_AS(model.mismatch_mse(p, 1e-4, fixed, power, {}, {}), InvalidInput);
    CHECK_THROWS_AS(model.mismatch_mse(p, 1e-4, fixed, power, cross, {Plane(m, m), Plane(m, m)}),
                    InvalidInput);
    CHECK_THROWS_AS(model.mismatch_mse(p, 1e-4, fixed, Plane(m, m / 2), cross, {}), InvalidInput);
}

}  // namespace pinmask
