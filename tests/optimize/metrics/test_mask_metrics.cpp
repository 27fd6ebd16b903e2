// optimize/metrics/mask_metrics and the spectral-zero check: the priors, and spectral zeros
// against patterns whose DFT is known in closed form.
#include <doctest/doctest.h>

#include <cmath>

#include "core/errors/error.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"

using namespace pinmask;

TEST_CASE("spectral zeros: two pinholes half a period apart vanish at every odd column") {
    // P^(k, l) = 1 + exp(-2 pi i 4 l / 8) = 1 + (-1)^l: exact zeros at odd l, any k.
    Pattern p;
    p.n = 8;
    p.pinholes = {{0, 0}, {0, 4}};
    const ComplexPlane spectrum = pattern_spectrum(p);
    const int m = 16;
    const ComplexPlane all_pass = ComplexPlane::Constant(m, m, {1.0, 0.0});
    const auto passed = pattern_frequencies_passed(all_pass, 8);
    const SpectralZero z = find_spectral_zero(spectrum, passed);
    CHECK(z.found);
    CHECK(z.count == 8 * 4);  // 8 rows x 4 odd columns
    CHECK(z.col % 2 == 1);
    CHECK(z.abs_value < 1e-12);
    CHECK(z.message().find("spectral zero at pattern frequency") != std::string::npos);

    // A kernel that passes no light at odd columns (nor their aliases l + 8): no flag.
    ComplexPlane blocked = all_pass;
    for (int k = 0; k < m; ++k)
        for (int l = 1; l < m; l += 2) blocked(k, l) = 0.0;
    CHECK_FALSE(find_spectral_zero(spectrum, pattern_frequencies_passed(blocked, 8)).found);

    // A single pinhole has a flat spectrum |P^| = 1 = sqrt(K): never a zero.
    p.pinholes = {{3, 5}};
    CHECK_FALSE(find_spectral_zero(pattern_spectrum(p), passed).found);
    CHECK_THROWS_AS(find_spectral_zero(spectrum, passed, 0.0), InvalidInput);
}

TEST_CASE("priors: natural, text and stars differ, are seeded, and validate their counts") {
    const int m = 32;
    PriorSpec natural;
    natural.count = 2;
    PriorSpec text = natural, stars = natural;
    text.kind = PriorKind::kText;
    stars.kind = PriorKind::kStars;
    const ScenePrior a = make_scene_prior(natural, m), b = make_scene_prior(text, m),
                     c = make_scene_prior(stars, m);
    // Same spec, same prior (byte-identical power).
    CHECK((make_scene_prior(text, m).power == b.power).all());
    // Text pages are mostly paper (mean near 1), stars mostly sky (mean near 0).
    CHECK(b.mean > 0.6);
    CHECK(c.mean < 0.05);
    CHECK(a.mean > 0.2);
    CHECK(a.mean < 0.8);
    // Stars are points: a much flatter spectrum (relative to DC) than natural 1/f textures.
    const auto ratio = [m](const ScenePrior& p) { return p.power(m / 2, m / 2) / p.power(0, 0); };
    CHECK(ratio(c) > 10.0 * ratio(a));
    PriorSpec bad = natural;
    bad.count = 0;
    CHECK_THROWS_WITH_AS(bad.validate(), doctest::Contains("`prior.count`"), InvalidInput);
    CHECK_THROWS_WITH_AS(parse_prior_spec("no-such-prior"), doctest::Contains("`prior`"),
                         InvalidInput);
    CHECK(parse_prior_spec("stars").kind == PriorKind::kStars);
}

TEST_CASE(
    "prior relevance: a prior with power only at low frequencies leaves the rest irrelevant") {
    ScenePrior p;
    p.power = Plane::Zero(8, 8);
    p.power(0, 0) = 100.0;
    p.power(0, 1) = p.power(0, 7) = 1.0;  // radius 1 along columns
    p.power(3, 3) = 1e-9;                 // below 1e-6 of the peak
    const PriorRelevance r = prior_relevance(p);
    CHECK(r.total == 63);
    CHECK(r.irrelevant == 61);
    CHECK(r.highest_relevant_radius == doctest::Approx(1.0));
}
