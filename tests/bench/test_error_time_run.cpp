// bench/error_time_run against the parts it composes, called here directly: the set-up's PSF and
// scenes, the sweep's records (qualities are deterministic per seed), and one plot per SNR.
#include <doctest/doctest.h>

#include <random>

#include "bench/error_time_run.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"

using namespace pinmask;

TEST_CASE("error-time run: set-up, sweep and plots equal the parts called directly") {
    Mask mask;
    mask.camera = paper_camera();
    std::mt19937_64 rng(3);
    RandomSparseOptions rs;
    rs.n = 6;
    rs.holes = 4;
    mask.pattern = random_sparse_pattern(rs, rng);
    mask.psf.pixels_per_cell = 4;

    const std::vector<SceneSpec> specs{scene_from_name("usaf"), scene_from_name("point")};
    const ErrorTimeSetup setup = error_time_setup(mask, specs);
    const Plane psf = synthesize_psf(mask.pattern, mask_kernel(mask), 4);
    REQUIRE(setup.period_px == 24);
    CHECK((setup.psf.array() == psf.array()).all());
    REQUIRE(setup.scenes.size() == 2);
    CHECK(setup.scenes[1].name == "point");
    CHECK((setup.scenes[0].image.channels[0].array() ==
           make_scene(specs[0], 24, 24).channels[0].array())
              .all());

    ErrorTimeOptions o;
    o.snr_db = {30.0, 20.0};
    o.iterations = {1, 4};
    o.wiener_nsr = {1e-2};
    o.tikhonov_lambda = {1e-3};
    o.repeats = 1;
    const ErrorTimeResult r = run_error_time_bench(setup, o, "test mask");
    const std::vector<ErrorTimeRecord> ref = run_error_time(psf, setup.scenes, o);
    REQUIRE(r.records.size() == ref.size());
    for (std::size_t i = 0; i < ref.size(); ++i) {
        CHECK(r.records[i].decoder == ref[i].decoder);
        CHECK(r.records[i].psnr_db == ref[i].psnr_db);  // same seed, same decode: exact
    }
    CHECK(r.points.size() == mean_over_scenes(ref).size());
    REQUIRE(r.plots.size() == 2);
    CHECK(r.plots[0].stem == "error_time_snr30");
    CHECK(r.plots[1].stem == "error_time_snr20");
    for (const auto& p : r.plots[1].plot.points) CHECK(p.snr_db == 20.0);
    CHECK(r.plots[0].plot.subtitle.find("mask: test mask; 24 x 24 period; scenes: usaf, point") ==
          0);
    CHECK(!r.markdown.empty());
}

TEST_CASE("error-time run: the paper preset is `generate --family paper --seed 1`") {
    const Mask m = error_time_paper_mask();
    std::mt19937_64 rng(1);
    CHECK(m.pattern.pinholes == paper_pattern(rng).pinholes);
    CHECK(m.psf.pixels_per_cell == 8);
    CHECK(error_time_number(30.0) == "30");
    CHECK(error_time_number(2.5) == "2.5");
}
