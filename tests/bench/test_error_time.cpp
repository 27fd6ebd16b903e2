#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>

#include "bench/error_time.hpp"
#include "bench/error_time_plot.hpp"
#include "bench/error_time_report.hpp"
#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"
#include "optimize/simulate/scenes.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

// Averages of a few doubles: rounding only.
constexpr double kMeanTol = 1e-12;

// A 6 x 6 random pattern with a one-pixel kernel at 4 pixels per cell (a 24 x 24 period): the
// OTF is P^(k mod n) / K, checked free of zeros, so a near-noiseless Wiener decode is exact.
Plane small_psf() {
    std::mt19937_64 rng(3);
    RandomSparseOptions r;
    r.n = 6;
    r.holes = 4;
    const Pattern p = random_sparse_pattern(r, rng);
    REQUIRE(pattern_spectrum(p).abs().minCoeff() > 1e-3);
    return synthesize_psf(p, measured_kernel(Plane::Ones(1, 1), 4, "delta"), 4);
}

std::vector<NamedScene> small_scenes() {
    return {{"usaf", make_scene(scene_from_name("usaf"), 24, 24)},
            {"natural", make_scene(scene_from_name("natural"), 24, 24)}};
}

ErrorTimeOptions quick() {
    ErrorTimeOptions o;
    o.iterations = {1, 4, 20};
    o.wiener_nsr = {1e-12, 1e-2};
    o.tikhonov_lambda = {1e-3};
    o.repeats = 1;
    return o;
}

int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

ErrorTimeRecord rec(const char* scene, const char* decoder, int iterations, double value,
                    double seconds, double psnr) {
    ErrorTimeRecord r;
    r.snr_db = 30;
    r.scene = scene;
    r.decoder = decoder;
    r.parameter = iterations == 0 ? "nsr" : "";
    r.value = value;
    r.iterations = iterations;
    r.seconds = seconds;
    r.wall_seconds = 2 * seconds;
    r.psnr_db = psnr;
    r.ssim = psnr / 100;
    return r;
}

}  // namespace

TEST_CASE("error-time sweep: every setting on every scene, exact iteration counts") {
    ErrorTimeOptions o = quick();
    o.snr_db = {30.0, 20.0};
    const std::vector<NamedScene> scenes = small_scenes();
    const auto records = run_error_time(small_psf(), scenes, o);
    const std::size_t per_scene = 2 + 1 + 3 * 3;
    REQUIRE(records.size() == per_scene * scenes.size() * o.snr_db.size());
    for (const auto& r : records) {
        CAPTURE(r.decoder);
        CHECK(r.seconds >= 0.0);
        CHECK(r.wall_seconds >= 0.0);
        CHECK(std::isfinite(r.psnr_db));
        CHECK(std::isfinite(r.ssim));
        CHECK(r.timing_runs == 1);
        if (r.iterations > 0) CHECK(r.iterations_run == r.iterations);  // tolerance 0
    }
    CHECK(records.front().snr_db == 30.0);
    CHECK(records.back().snr_db == 20.0);
    CHECK(records.front().scene == "usaf");
    // TVQC's eps follows the l1-magic rule from the noise sigma: more noise, larger eps.
    double eps30 = 0, eps20 = 0;
    for (const auto& r : records) {
        if (r.decoder != "tvqc" || r.scene != "usaf") continue;
        (r.snr_db == 30.0 ? eps30 : eps20) = r.value;
    }
    CHECK(eps20 > 3.0 * eps30);  // sigma grows by 10^(10/20) = 3.16
}

TEST_CASE("error-time: a near-noiseless capture decodes exactly with Wiener at a tiny NSR") {
    ErrorTimeOptions o = quick();
    o.snr_db = {250.0};
    const auto records = run_error_time(small_psf(), small_scenes(), o);
    for (const auto& r : records) {
        if (r.decoder == "wiener" && r.value == 1e-12) CHECK(r.psnr_db > 100.0);
    }
}

TEST_CASE("error-time: qualities are deterministic per seed; repeats give the median") {
    ErrorTimeOptions o = quick();
    const auto a = run_error_time(small_psf(), small_scenes(), o);
    o.repeats = 3;
    o.repeat_below_seconds = 1e9;  // repeat everything
    const auto b = run_error_time(small_psf(), small_scenes(), o);
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].psnr_db == b[i].psnr_db);
        CHECK(a[i].ssim == b[i].ssim);
        CHECK(b[i].timing_runs == 3);
    }
    o.seed = 2;
    const auto c = run_error_time(small_psf(), small_scenes(), o);
    CHECK(c[0].psnr_db != a[0].psnr_db);
}

TEST_CASE("mean over scenes and the per-decoder summary") {
    const std::vector<ErrorTimeRecord> r{
        rec("a", "wiener", 0, 0.01, 0.001, 20), rec("b", "wiener", 0, 0.01, 0.003, 24),
        rec("a", "wiener", 0, 0.1, 0.001, 10),  rec("b", "wiener", 0, 0.1, 0.001, 12),
        rec("a", "tvqc", 10, 0, 0.1, 25),       rec("b", "tvqc", 10, 0, 0.3, 27),
        rec("a", "tvqc", 100, 0, 1.0, 26.1),    rec("b", "tvqc", 100, 0, 1.0, 26.0)};
    const auto points = mean_over_scenes(r);
    REQUIRE(points.size() == 4);
    CHECK(points[0].decoder == "wiener");
    CHECK(points[0].scenes == 2);
    CHECK_CLOSE(points[0].psnr_db, 22.0, kMeanTol);
    CHECK_CLOSE(points[0].seconds, 0.002, kMeanTol);
    CHECK_CLOSE(points[0].wall_seconds, 0.004, kMeanTol);
    CHECK_CLOSE(points[1].psnr_db, 11.0, kMeanTol);
    CHECK_CLOSE(points[2].psnr_db, 26.0, kMeanTol);
    CHECK_CLOSE(points[3].psnr_db, 26.05, kMeanTol);
    const auto s = summarise_decoders(points, kNearBestDb);
    REQUIRE(s.size() == 2);
    CHECK(s[0].best.value == 0.01);
    CHECK(s[0].near_best.value == 0.01);  // closed form: no budget to trade
    CHECK(s[1].best.iterations == 100);
    CHECK(s[1].near_best.iterations == 10);  // 26.0 is within 0.1 dB of 26.05, and faster
    const auto s2 = summarise_decoders(points, 0.01);
    CHECK(s2[1].near_best.iterations == 100);
}

TEST_CASE("error-time reports: CSV lines, Markdown rows, plots in both formats") {
    const auto records = run_error_time(small_psf(), small_scenes(), quick());
    const auto points = mean_over_scenes(records);
    const std::string csv = error_time_csv(records);
    CHECK(count_lines(csv) == static_cast<int>(records.size()) + 1);
    CHECK(csv.rfind("snr_db,scene,decoder,", 0) == 0);
    CHECK(count_lines(error_time_points_csv(points)) == static_cast<int>(points.size()) + 1);
    const std::string md = error_time_markdown(summarise_decoders(points, kNearBestDb));
    for (const char* d : {"| wiener |", "| tikhonov |", "| tv-l2 |", "| tvqc |",
                          "| richardson-lucy |", "TVQC 7.2 s"}) {
        INFO(d);
        CHECK(md.find(d) != std::string::npos);
    }

    test::TempDir dir("error-time-plot");
    ErrorTimePlot plot{"title", "subtitle", points};
    write_error_time_svg(dir / "p.svg", plot);
    write_error_time_png(dir / "p.png", plot);
    CHECK(test::slurp(dir / "p.svg").find("<svg") != std::string::npos);
    const LoadedImage png = read_image(dir / "p.png");
    CHECK(png.image.cols() == kPlotWidth);
    CHECK(png.image.rows() == kPlotHeight);
    CHECK_THROWS_AS(write_error_time_png(dir / "q.png", ErrorTimePlot{}), InvalidInput);
    CHECK(!std::filesystem::exists(dir / "q.png"));
}

TEST_CASE("error-time validation names the field") {
    const Plane psf = small_psf();
    auto bad = [&](auto change, const char* field) {
        ErrorTimeOptions o = quick();
        change(o);
        INFO(field);
        try {
            run_error_time(psf, small_scenes(), o);
            CHECK(false);
        } catch (const InvalidInput& e) {
            CHECK(std::string(e.what()).find(field) != std::string::npos);
        }
    };
    bad([](ErrorTimeOptions& o) { o.iterations = {0}; }, "iterations");
    bad([](ErrorTimeOptions& o) { o.wiener_nsr = {-1}; }, "wiener_nsr");
    bad([](ErrorTimeOptions& o) { o.tv_lambda = 0; }, "tv_lambda");
    bad([](ErrorTimeOptions& o) { o.repeats = 0; }, "repeats");
    bad([](ErrorTimeOptions& o) { o.snr_db = {}; }, "snr_db");
    CHECK_THROWS_AS(run_error_time(psf, {}, quick()), InvalidInput);
    const std::vector<NamedScene> wrong{{"usaf", make_scene(scene_from_name("usaf"), 20, 24)}};
    CHECK_THROWS_AS(run_error_time(psf, wrong, quick()), InvalidInput);
}
