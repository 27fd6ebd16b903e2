#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/errors/error.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

// Sample mean/variance of 256^2 independent draws: the relative standard error of a variance
// estimate is sqrt(2 / 65536) = 0.55 %; 3 % is more than five standard errors.
constexpr double kSampleVarianceTol = 0.03;
constexpr int kSide = 256;

double sample_variance(const Plane& p) { return (p - p.mean()).square().sum() / (p.size() - 1); }

}  // namespace

TEST_CASE("validation names the field") {
    NoiseModel m;
    m.kind = NoiseKind::kPhoton;
    m.photons_per_pinhole = -1;
    CHECK_THROWS_WITH_AS(validate(m), doctest::Contains("photons_per_pinhole"), InvalidInput);
    m.photons_per_pinhole = 10;
    m.adc_bits = 8;
    CHECK_THROWS_WITH_AS(validate(m), doctest::Contains("full_well_e"), InvalidInput);
    m.full_well_e = 1e4;
    CHECK_NOTHROW(validate(m));
    m.film_optical_density = -0.5;
    CHECK_THROWS_WITH_AS(validate(m), doctest::Contains("film_optical_density"), InvalidInput);
    NoiseModel g;
    g.snr_db = std::nan("");
    CHECK_THROWS_WITH_AS(validate(g), doctest::Contains("snr_db"), InvalidInput);
}

TEST_CASE("Gaussian: sigma from the SNR definition, and the sampler honours it") {
    CHECK_CLOSE(sigma_for_snr(0.25, 20.0), std::sqrt(0.25 / 100.0), 1e-15);
    NoiseModel m;
    m.snr_db = 25.0;
    std::mt19937_64 rng(1);
    Plane clean(kSide, kSide);
    for (int r = 0; r < kSide; ++r)
        for (int c = 0; c < kSide; ++c) clean(r, c) = 0.5 + 0.4 * std::sin(0.1 * r + 0.2 * c);
    const Plane noisy = add_noise(clean, m, 1, 1, rng);
    const double expect = clean.square().mean() / std::pow(10.0, 2.5);
    CHECK_CLOSE(sample_variance(noisy - clean), expect, kSampleVarianceTol);
    CHECK_CLOSE(mean_noise_variance(m, {clean.mean(), clean.square().mean(), 1, 1}), expect, 1e-12);
    std::mt19937_64 rng2(1);
    CHECK((add_noise(clean, m, 1, 1, rng2) == noisy).all());  // same seed, same draw
}

TEST_CASE("photon model: sampled mean and variance match the variance function") {
    NoiseModel m;
    m.kind = NoiseKind::kPhoton;
    m.photons_per_pinhole = 300.0;
    m.read_noise_e = 20.0;
    m.dark_current_e = 50.0;
    m.film_optical_density = 2.0;  // T = 0.01
    m.full_well_e = 1e6;
    const int open = 12, total = 256;
    const double c = 0.4;
    const Plane clean = Plane::Constant(kSide, kSide, c);
    // By hand: signal 300*12*0.4 = 1440 e, leak 300*0.01*244*0.4 = 292.8 e, dark 50 e,
    // read 400 e^2; scale 3600 e per unit.
    const double expect = (1440.0 + 292.8 + 50.0 + 400.0) / (3600.0 * 3600.0);
    CHECK_CLOSE(mean_noise_variance(m, {c, c * c, open, total}), expect, 1e-12);
    CHECK_CLOSE(dark_offset_e(m, {c, c * c, open, total}), 342.8, 1e-12);
    std::mt19937_64 rng(2);
    const Plane noisy = add_noise(clean, m, open, total, rng);
    // The mean is unbiased: |mean - c| within 5 standard errors of the mean.
    CHECK(std::fabs(noisy.mean() - c) <= 5.0 * std::sqrt(expect / noisy.size()));
    CHECK_CLOSE(sample_variance(noisy), expect, kSampleVarianceTol);

    // Quantisation adds q^2 / 12 when the noise spans a few ADC steps.
    m.adc_bits = 8;
    m.full_well_e = 20000.0;
    const double q = 20000.0 / 255.0;
    const double expect_q = (1440.0 + 292.8 + 50.0 + 400.0 + q * q / 12.0) / (3600.0 * 3600.0);
    CHECK_CLOSE(mean_noise_variance(m, {c, c * c, open, total}), expect_q, 1e-12);
    CHECK_CLOSE(sample_variance(add_noise(clean, m, open, total, rng)), expect_q,
                kSampleVarianceTol);
}

TEST_CASE("photon model: saturation clips to the full well") {
    NoiseModel m;
    m.kind = NoiseKind::kPhoton;
    m.photons_per_pinhole = 1000.0;
    m.full_well_e = 500.0;  // far below the 1000 * 4 * 0.5 = 2000 e signal
    std::mt19937_64 rng(3);
    const Plane noisy = add_noise(Plane::Constant(8, 8, 0.5), m, 4, 64, rng);
    CHECK((noisy == 500.0 / 4000.0).all());
}

TEST_CASE("photon model: more pinholes, less relative shot noise (the multiplexing gain)") {
    NoiseModel m;
    m.kind = NoiseKind::kPhoton;
    m.photons_per_pinhole = 100.0;
    m.read_noise_e = 5.0;
    double previous = std::numeric_limits<double>::infinity();
    for (int k : {1, 4, 16, 64}) {
        const double v = mean_noise_variance(m, {0.5, 0.3, k, 256});
        CHECK(v < previous);
        previous = v;
    }
    std::mt19937_64 rng(4);
    CHECK_THROWS_AS(add_noise(Plane::Constant(2, 2, -0.1), m, 1, 4, rng), InvalidInput);
}

TEST_CASE("huge electron counts: bounded with the reason, and no hang in the Poisson draw") {
    NoiseModel m;
    m.kind = NoiseKind::kPhoton;
    m.photons_per_pinhole = 1e18;
    CHECK_THROWS_WITH_AS(validate(m), doctest::Contains("at most 1e12"), InvalidInput);
    m.photons_per_pinhole = 10.0;
    m.dark_current_e = 1e19;
    CHECK_THROWS_WITH_AS(validate(m), doctest::Contains("dark_current_e"), InvalidInput);
    NoiseModel g;
    g.snr_db = 1e300;
    CHECK_THROWS_WITH_AS(validate(g), doctest::Contains("300"), InvalidInput);

    // At the bound the sampler takes the normal approximation: mean and variance of the
    // normalised capture as the model says (variance ppp K c / (ppp K)^2 = c / (ppp K)).
    m.dark_current_e = 0.0;
    m.photons_per_pinhole = kMaxElectrons;
    const Plane clean = Plane::Constant(kSide, kSide, 0.5);
    std::mt19937_64 rng(3);
    const Plane noisy = add_noise(clean, m, 1, 4, rng);
    const double expected_var = 0.5 / kMaxElectrons;
    CHECK(std::abs(noisy.mean() - 0.5) < 5.0 * std::sqrt(expected_var / noisy.size()));
    CHECK(sample_variance(noisy) == doctest::Approx(expected_var).epsilon(kSampleVarianceTol));
}
