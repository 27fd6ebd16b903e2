// Choosing the pinhole count: search --holes A..B against random masks of every
// single K, under the photon model at dim light, judged by simulated Wiener decoding of real
// photographs the project never saw (Debian's python3-skimage data set; the search's prior is
// synthetic 1/f scenes) and by the expected PSNR over a large independent sample of the
// synthetic scene family (seeds 20000..).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <random>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "optimize/simulate/scenes.hpp"

using namespace pinmask;

namespace {

// The requirement: the searched mask beats the best per-K random median by >= 0.5 dB of held-out
// simulated Wiener PSNR on natural images the project never saw. Measured (docs/benchmarks.md
// "Choosing K at dim light", search seeds 1..3): on a 32 x 32 grid 0.86-0.93 dB on the photographs
// and 0.61-0.63 dB expected over the synthetic family; on the paper's 16 x 16 grid 0.48-0.56 dB on
// the photographs, 0.40-0.43 dB expected. At dim light the capture is shot-noise limited,
// |H|^2 / sigma^2 ~ (|P^|^2 / K^2) (3 K mean) hardly grows with K, and the pattern only shapes
// its spectrum's dips: on 16 x 16 every search route ends near 0.4 dB expected and the bound
// (objective_bound_autocorr) leaves at most 0.63 dB (tuned NSR). The 32 x 32 test holds the bar
// on both measures; the 16 x 16 test holds 0.3 dB on both.
constexpr double kRequiredGainDb = 0.5;
constexpr double kPaperGridGainDb = 0.3;  // what the 16 x 16 test holds, with margin
// Real photographs, turned grey and area-resampled to the period (file_scene): people, animals,
// objects, the moon, textures. PINMASK_PHOTO_DIR is skimage's data folder (tests/CMakeLists.txt).
constexpr const char* kPhotos[] = {"astronaut.png",       "camera.png", "chelsea.png", "coffee.png",
                                   "motorcycle_left.png", "coins.png",  "moon.png",    "brick.png",
                                   "grass.png",           "gravel.png"};
constexpr int kPhotoCount = static_cast<int>(std::size(kPhotos));
constexpr std::uint64_t kExpectationFirstSeed = 20000;
constexpr int kExpectationScenes = 1024;

Mask paper_template(int n) {
    Mask m;
    m.camera = paper_camera();
    m.pattern.n = n;
    m.pattern.tiles_rows = m.pattern.tiles_cols = 2;
    m.pattern.min_spacing_cells = 2.0;
    m.psf.pixels_per_cell = 8;
    return m;
}

NoiseModel dim_light() {
    NoiseModel nm;
    nm.kind = NoiseKind::kPhoton;
    nm.photons_per_pinhole = 3.0;  // electrons per pinhole per pixel
    nm.read_noise_e = 3.0;
    return nm;
}

struct HeldOut {
    std::vector<NamedScene> scenes;
    SimulatedMetricsOptions sim;
    NoiseModel noise = dim_light();

    double psnr(const Mask& mask) const {
        const int k = static_cast<int>(mask.pattern.pinholes.size());
        return simulated_quality(mask_psf(mask), scenes, noise, k, mask.pattern.n * mask.pattern.n,
                                 SimulatedDecoder::kWiener, sim)
            .mean_psnr_db;
    }
};

// One measurement on an n x n grid: search --holes 5..40 (its default filter: Wiener
// with the NSR tuned per mask under --photons) against `draws` random valid masks of every
// single K, by held-out simulated Wiener PSNR (tuned NSR) on the first `scenes` of kPhotos, and
// by the expected PSNR over the family (the tuned-NSR closed form on
// 1024 scenes of other seeds; it predicts the simulation,
// tests/optimize/metrics/test_dim_light_model).
struct DimLightResult {
    int found_k = 0, best_k = 0, best_expected_k = 0;
    double found_psnr = 0.0, best_median = -INFINITY;
    double found_expected = 0.0, best_expected_median = -INFINITY;
};

struct DimLightSizes {
    int n = 16;                            // grid
    int scenes = kPhotoCount;              // held-out photographs
    int draws = 7;                         // random masks per K
    long evaluations = 6000;               // search evaluations (one chain)
    int expectation = kExpectationScenes;  // scenes of the expectation's family
    std::uint64_t seed = 1;                // the search's seed
};

// The held-out photographs are python3-skimage's data set, an optional package: without it the
// dim-light cases say so (naming the package) and check nothing.
bool photos_available() {
    const std::filesystem::path photo_dir = PINMASK_PHOTO_DIR;
    if (std::filesystem::is_regular_file(photo_dir / kPhotos[0])) return true;
    MESSAGE(
        "skipped: python3-skimage is not installed (its photographs are the held-out scenes; "
        "scripts/install-deps --with-optional installs it); looked in '"
        << photo_dir.string() << "'");
    return false;
}

DimLightResult dim_light_search_against_random(const DimLightSizes& z) {
    const int n = z.n, scenes = z.scenes, draws = z.draws;
    const long evaluations = z.evaluations;
    const Mask tmpl = paper_template(n);
    const int m = n * tmpl.psf.pixels_per_cell;
    HeldOut held;
    const std::filesystem::path photo_dir = PINMASK_PHOTO_DIR;
    for (int i = 0; i < scenes; ++i) {
        const Image photo = file_scene(photo_dir / kPhotos[i], m, m);
        Plane grey = Plane::Zero(m, m);
        for (const Plane& c : photo.channels) grey += c / photo.n_channels();
        held.scenes.push_back({kPhotos[i], Image(grey)});
    }
    held.sim.seed = 99;
    held.sim.wiener_nsr = {true, 0.01};  // every mask gets its best NSR

    SearchPipelineOptions o;
    o.tmpl = tmpl;
    o.holes = 5;
    o.max_holes = 40;
    o.noise = dim_light();
    o.filter = parse_search_filter("auto", o.noise);  // search's default: tuned NSR here
    CHECK(o.filter.kind == WienerFilterKind::kTunedNsr);
    o.search.threads = 1;
    o.search.seed = z.seed;
    o.search.time_budget_s = 0.0;
    o.search.max_evaluations = evaluations;
    o.search.anneal_restart_moves = evaluations / 2;
    o.search.top = 1;
    o.rerank_scenes.clear();
    const SearchPipelineSummary s = run_search_pipeline(o);
    REQUIRE(!s.ranked.empty());
    REQUIRE(!s.best_per_holes.empty());
    const Mask& found = s.ranked.front().mask;
    DimLightResult r;
    r.found_k = static_cast<int>(found.pattern.pinholes.size());
    CHECK(r.found_k >= 5);
    CHECK(r.found_k <= 40);
    CHECK(spacing_violations(found.pattern).empty());
    r.found_psnr = held.psnr(found);

    PriorSpec family;
    family.count = z.expectation;
    family.first_seed = kExpectationFirstSeed;
    const AnalyticWienerModel expectation(
        expand_half_spectrum(kernel_spectrum(mask_kernel(tmpl), n, tmpl.psf.pixels_per_cell), m),
        make_scene_prior(family, m), dim_light());
    const auto expected_psnr = [&](const Mask& mask) {
        return expectation.evaluate_tuned_nsr(pattern_spectrum(mask.pattern)).psnr_db;
    };
    r.found_expected = expected_psnr(found);

    // Random baseline: for every K in 5..40, `draws` random valid masks; the median by held-out
    // simulated Wiener PSNR (as compare's random-median baseline); the best K's median.
    for (int k = 5; k <= 40; ++k) {
        RandomSparseOptions ro;
        ro.n = n;
        ro.holes = k;
        std::vector<double> psnr, expected;
        for (int d = 0; d < draws; ++d) {
            std::mt19937_64 rng(static_cast<std::uint64_t>(1000 * k + d));
            Mask mask = tmpl;
            mask.pattern = random_sparse_pattern(ro, rng);
            psnr.push_back(held.psnr(mask));
            expected.push_back(expected_psnr(mask));
        }
        std::sort(psnr.begin(), psnr.end());
        std::sort(expected.begin(), expected.end());
        const double median = psnr[psnr.size() / 2];
        if (median > r.best_median) r.best_median = median, r.best_k = k;
        const double expected_median = expected[expected.size() / 2];
        if (expected_median > r.best_expected_median)
            r.best_expected_median = expected_median, r.best_expected_k = k;
    }
    MESSAGE(n << " x " << n << ", search seed " << z.seed << ": searched K = " << r.found_k << ": "
              << r.found_psnr << " dB held out; best random median: K = " << r.best_k << ", "
              << r.best_median << " dB");
    MESSAGE("expected over the family: searched "
            << r.found_expected << " dB; best random median: K = " << r.best_expected_k << ", "
            << r.best_expected_median << " dB");
    return r;
}

}  // namespace

TEST_CASE(
    "search --holes 5..40 against random masks of every K at dim light, 32 x 32: the "
    "measurement runs (its 0.5 dB bar: the slow case over seeds 1 2 3)") {
    // The default run checks the machinery on a small run (one photograph, one draw, 200
    // evaluations, a 16-scene family): the full measurement (10 photographs, 9 random masks per
    // K, 20000 evaluations) took 150-350 s, the largest share of the suite. The bar itself is
    // held by the slow case below over search seeds 1, 2, 3 (seed 1 is this one's), CTest
    // slow-dim-light-32-seeds.
    if (!photos_available()) return;
    const DimLightResult r = dim_light_search_against_random({32, 1, 1, 200, 16});
    CHECK(std::isfinite(r.found_psnr));
    CHECK(std::isfinite(r.found_expected));
    CHECK(r.best_k >= 5);
    CHECK(r.best_k <= 40);
}

TEST_CASE("at the paper's 16 x 16 grid the dim-light search gains what the grid allows") {
    // 10 photographs, 7 random masks per K, 6000 evaluations; same sizes sanitized. Measured
    // 0.49 dB on the photographs and 0.40 dB expected (see the top of this file).
    if (!photos_available()) return;
    const DimLightResult r = dim_light_search_against_random({});
    CHECK(r.found_psnr >= r.best_median + kPaperGridGainDb);
    CHECK(r.found_expected >= r.best_expected_median + kPaperGridGainDb);
}

// Slow (CTest slow-dim-light-32-seeds, label slow; about 5 minutes): the 32 x 32 measurement
// over search seeds 1, 2, 3. Reproduces the 32 x 32 rows of docs/benchmarks.md "Choosing K at
// dim light": gains 0.93, 0.86, 0.89 dB on the photographs and 0.63, 0.61, 0.61 dB expected, so
// each seed holds the 0.5 dB requirement on both measures with a margin of at least 0.36 dB
// (photographs) and 0.11 dB (expected).
TEST_CASE("dim light 32 x 32 over search seeds 1 2 3: the 0.5 dB gain on every seed" *
          doctest::skip()) {
    if (!photos_available()) return;
    for (const std::uint64_t seed : {1, 2, 3}) {
        CAPTURE(seed);
        DimLightSizes z{32, kPhotoCount, 9, 20000};
        z.seed = seed;
        const DimLightResult r = dim_light_search_against_random(z);
        CHECK(r.found_psnr >= r.best_median + kRequiredGainDb);
        CHECK(r.found_expected >= r.best_expected_median + kRequiredGainDb);
    }
}

// Slow (CTest slow-dim-light-16-seeds, label slow; about a minute): the paper's 16 x 16 grid
// over search seeds 1, 2, 3. Reproduces the 16 x 16 rows of docs/benchmarks.md "Choosing K at
// dim light": gains 0.49, 0.53, 0.56 dB on the photographs and 0.40, 0.41, 0.43 dB expected, so
// each seed holds kPaperGridGainDb (0.3 dB) with a margin of at least 0.19 dB (photographs) and
// 0.10 dB (expected).
TEST_CASE("dim light 16 x 16 over search seeds 1 2 3: 0.3 dB on every seed" * doctest::skip()) {
    if (!photos_available()) return;
    for (const std::uint64_t seed : {1, 2, 3}) {
        CAPTURE(seed);
        DimLightSizes z;
        z.seed = seed;
        const DimLightResult r = dim_light_search_against_random(z);
        CHECK(r.found_psnr >= r.best_median + kPaperGridGainDb);
        CHECK(r.found_expected >= r.best_expected_median + kPaperGridGainDb);
    }
}

TEST_CASE(
    "parse_search_filter: auto by the noise model, else parse_wiener_filter; bad text names "
    "every choice") {
    NoiseModel gauss;
    CHECK(parse_search_filter("auto", gauss).kind == WienerFilterKind::kOptimal);
    CHECK(parse_search_filter("auto", dim_light()).kind == WienerFilterKind::kTunedNsr);
    CHECK(parse_search_filter("nsr:0.5", gauss).nsr == 0.5);
    CHECK_THROWS_WITH_AS(parse_search_filter("bogus", gauss), doctest::Contains("'auto'"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(parse_search_filter("nsr:-1", gauss), doctest::Contains("must be > 0"),
                         InvalidInput);
}

TEST_CASE("parse_holes_range: K or A..B, anything else names --holes") {
    CHECK(parse_holes_range("20") == std::pair<int, int>{20, 0});
    CHECK(parse_holes_range("5..40") == std::pair<int, int>{5, 40});
    CHECK(parse_holes_range("7..7") == std::pair<int, int>{7, 7});
    for (const char* bad : {"", "0", "-3", "5..4", "0..4", "a..b", "5..", "..5", "5...7", "1e3",
                            "5 ..7", "1234567890..2"}) {
        INFO(bad);
        CHECK_THROWS_WITH_AS(parse_holes_range(bad), doctest::Contains("`holes`"), InvalidInput);
    }
}

TEST_CASE("a pinhole-count range above the packing bound is refused, naming --holes") {
    SearchPipelineOptions o;
    o.tmpl = paper_template(16);
    o.holes = 5;
    o.max_holes = 65;  // s = 2 on 16 x 16: at most 64 (design/pattern/packing_bound)
    o.search.time_budget_s = 0.0;
    o.search.max_evaluations = 10;
    CHECK_THROWS_WITH_AS(o.validate(), doctest::Contains("at most 64"), InvalidInput);
    o.max_holes = 4;
    CHECK_THROWS_WITH_AS(o.validate(), doctest::Contains("A <= B"), InvalidInput);
    o.max_holes = 64;
    CHECK_NOTHROW(o.validate());
}
