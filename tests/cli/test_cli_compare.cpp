// `pinmask compare` end to end on masks written with io/mask_json (a small geometry so the
// simulated figures stay fast: 8 x 8 cells of 4 pixels, a 32 x 32 period, one scene, short TV).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "design/optics/camera.hpp"
#include "design/pattern/random_sparse.hpp"
#include "io/mask_json.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;

namespace {

namespace fs = std::filesystem;

constexpr const char* kFast = " --scenes letter-R --tv-iters 30 ";

pinmask::Mask small_mask(std::uint64_t seed, int n = 8, int holes = 5) {
    pinmask::RandomSparseOptions ro;
    ro.n = n;
    ro.holes = holes;
    std::mt19937_64 rng(seed);
    pinmask::Mask m;
    m.camera = pinmask::paper_camera();
    m.pattern = pinmask::random_sparse_pattern(ro, rng);
    m.psf.pixels_per_cell = 4;
    m.provenance.seed = seed;
    m.provenance.generator = "test";
    m.provenance.family = "random";
    return m;
}

struct Masks {
    TempDir dir{"compare"};
    std::string a, b;
    Masks() {
        a = dir / "a.mask.json";
        b = dir / "b.mask.json";
        pinmask::io::write_mask_file(a, small_mask(1));
        pinmask::io::write_mask_file(b, small_mask(2));
    }
    // Files in the folder besides the two masks.
    std::size_t others() const {
        std::size_t k = 0;
        for (const auto& e : fs::directory_iterator(dir.path)) {
            const std::string f = e.path().filename().string();
            k += (f == "a.mask.json" || f == "b.mask.json") ? 0 : 1;
        }
        return k;
    }
};

std::size_t count(const std::string& hay, const std::string& needle) {
    std::size_t n = 0;
    for (auto i = hay.find(needle); i != std::string::npos; i = hay.find(needle, i + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("compare: two masks -> JSON table with unit-suffixed keys and a PDF report") {
    Masks m;
    const std::string report = m.dir / "r.pdf";
    const auto r =
        run_cli("compare " + m.a + " " + m.b + kFast + "--snr 25 --report " + report + " --json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["masks"].size() == 2);
    for (const auto& row : j["masks"]) {
        for (const char* key : {"name",
                                "kind",
                                "geometry_hash",
                                "n",
                                "holes",
                                "period_px",
                                "spacing_ok",
                                "max_sidelobe",
                                "peak_to_sidelobe_ratio",
                                "min_abs_pattern_spectrum",
                                "spectral_flatness",
                                "otf_condition_number",
                                "analytic_mmse_psnr_db",
                                "analytic_wiener_psnr_db",
                                "analytic_wiener_nsr",
                                "sim_wiener_psnr_db",
                                "sim_wiener_ssim",
                                "sim_wiener_nsr",
                                "sim_tv_psnr_db",
                                "sim_tv_ssim",
                                "sim_tv_lambda"}) {
            INFO(key);
            CHECK(row.contains(key));
        }
        CHECK(row["kind"] == "input");
        CHECK(row["holes"] == 5);
        CHECK(row["period_px"] == 32);
        CHECK(row["spacing_ok"] == true);
        CHECK(row["sim_wiener_ssim"].get<double>() <= 1.0);
    }
    // The second row's differences to the first: the lead figure exact, the simulated ones
    // paired over the scenes; one scene (kFast) gives no spread: no standard error, never
    // significant.
    CHECK_FALSE(j["masks"][0].contains("difference_to_first"));
    const auto& diff = j["masks"][1]["difference_to_first"];
    const std::string lead = j["lead_figure"]["name"];
    CHECK(lead == "analytic_mmse_psnr_db");  // generated masks: search's default under --snr
    CHECK(diff[lead]["exact"] == true);
    CHECK(diff[lead]["difference_db"].get<double>() ==
          j["masks"][1][lead].get<double>() - j["masks"][0][lead].get<double>());
    CHECK(diff["sim_wiener_psnr_db"]["exact"] == false);
    CHECK(diff["sim_wiener_psnr_db"]["samples"] == 1);
    CHECK(diff["sim_wiener_psnr_db"]["standard_error_db"].is_null());
    CHECK(diff["sim_wiener_psnr_db"]["significant"] == false);
    CHECK(diff["sim_wiener_psnr_db"]["difference_db"].get<double>() ==
          doctest::Approx(j["masks"][1]["sim_wiener_psnr_db"].get<double>() -
                          j["masks"][0]["sim_wiener_psnr_db"].get<double>())
              .epsilon(1e-12));
    CHECK(j["settings"]["noise"][0]["snr_db"] == 25.0);
    CHECK(!j.contains("baselines"));
    // Title page + one page per mask, in one PDF; the configuration beside it.
    const std::string pdf = slurp(report);
    CHECK(pdf.rfind("%PDF-", 0) == 0);
    CHECK(count(pdf, "/Type /Page") - count(pdf, "/Type /Pages") == 3);
    const auto config = nlohmann::json::parse(slurp(m.dir / "r.config.json"));
    CHECK(config["masks"] == j["masks"]);
    CHECK(m.others() == 2);

    // Same inputs, same bytes.
    const std::string again = m.dir / "again.pdf";
    REQUIRE(
        run_cli("compare " + m.a + " " + m.b + kFast + "--snr 25 --report " + again).exit_code ==
        0);
    CHECK(slurp(again) == pdf);
}

TEST_CASE("compare --baselines: random median, paper-like and MURA rows; SVG pages") {
    Masks m;
    const std::string report = m.dir / "r.svg";
    const auto r =
        run_cli("compare " + m.a + " " + m.b + kFast +
                "--baselines --baseline-count 5 --seed 3 --report " + report + " --json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["masks"].size() == 5);
    const auto& median = j["masks"][2];
    const auto& paper = j["masks"][3];
    const auto& mura = j["masks"][4];
    CHECK(median["kind"] == "random-median");
    CHECK(median["n"] == 8);  // the first mask's geometry
    CHECK(median["holes"] == 5);
    CHECK(paper["kind"] == "paper-like");
    CHECK(paper["n"] == 16);
    CHECK(paper["holes"] == 20);
    CHECK(mura["kind"] == "mura");
    CHECK(mura["n"] == 5);       // largest prime 4m + 1 <= 8
    CHECK(mura["holes"] == 12);  // (p^2 - 1) / 2
    CHECK(mura["spacing_ok"] == false);
    const auto& rnd = j["baselines"]["random"];
    CHECK(rnd["count"] == 5);
    // Ranked by the lead figure (the analytic MMSE PSNR under --snr for masks no search made).
    const std::string f = rnd["ranked_by"];
    CHECK(f == j["lead_figure"]["name"]);
    const double lo = rnd["min_" + f], mid = rnd["median_" + f], hi = rnd["max_" + f];
    CHECK(lo <= mid);
    CHECK(mid <= hi);
    // The median row is recomputed from the same model: the same figure.
    constexpr double kSameComputation = 1e-12;  // identical arithmetic, only printing differs
    CHECK(std::fabs(median[f].get<double>() - mid) <= kSameComputation * mid);
    // The first mask's gain over the median, with the median's standard error, in words too.
    const auto& gain = rnd["first_mask_gain"];
    CHECK(gain["difference_db"].get<double>() ==
          doctest::Approx(j["masks"][0][f].get<double>() - mid).epsilon(1e-12));
    CHECK(gain["standard_error_db"].get<double>() >= 0.0);
    CHECK(gain["standard_error_db"] == rnd["median_standard_error_db"]);
    CHECK(gain["text"].get<std::string>().find("standard error") != std::string::npos);
    // The median draw is reproducible with generate, as its source line says.
    const std::uint64_t seed = rnd["median_seed"];
    CHECK(seed >= 3);
    CHECK(seed < 8);
    const std::string regen = m.dir / "median.mask.json";
    REQUIRE(run_cli("generate --family random --grid 8 --holes 5 --pixels-per-cell 4 --seed " +
                    std::to_string(seed) + " -o " + regen)
                .exit_code == 0);
    const auto g = run_cli("compare " + regen + kFast + "--json");
    REQUIRE(g.exit_code == 0);
    CHECK(nlohmann::json::parse(g.out)["masks"][0]["geometry_hash"] == median["geometry_hash"]);

    // One SVG per page: title page + 5 mask pages.
    for (int p = 1; p <= 6; ++p) {
        const std::string svg = slurp(m.dir / ("r-" + std::to_string(p) + ".svg"));
        CHECK(svg.rfind("<?xml", 0) == 0);
        CHECK(svg.find("</svg>") != std::string::npos);
    }
    CHECK(!fs::exists(m.dir / "r-7.svg"));
    CHECK(j["report"].size() == 6);
}

TEST_CASE("compare prints a table; grid sizes may differ, each mask on its own period") {
    Masks m;
    const std::string c = m.dir / "c.mask.json";
    pinmask::io::write_mask_file(c, small_mask(4, 11, 6));  // n = 11 (prime), same camera
    const auto r = run_cli("compare " + m.a + " " + c + kFast);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("a.mask.json") != std::string::npos);
    CHECK(r.out.find("c.mask.json") != std::string::npos);
    CHECK(r.out.find("PSNR dB") != std::string::npos);
    // K differs (5 and 6): the PSNR-against-K view lists them by K with the light gain.
    const std::size_t view = r.out.find("PSNR against pinhole count");
    REQUIRE(view != std::string::npos);
    const std::size_t k5 = r.out.find("K 5  light 5x", view),
                      k6 = r.out.find("K 6  light 6x", view);
    CHECK(k5 != std::string::npos);
    CHECK(k6 != std::string::npos);
    CHECK(k5 < k6);
    const auto same = run_cli("compare " + m.a + " " + m.b + kFast);  // both K = 5: no view
    REQUIRE(same.exit_code == 0);
    CHECK(same.out.find("PSNR against pinhole count") == std::string::npos);
    const auto j = run_cli("compare " + m.a + " " + c + kFast + "--json");
    REQUIRE(j.exit_code == 0);
    CHECK(nlohmann::json::parse(j.out)["masks"][1]["period_px"] == 44);
}

TEST_CASE("compare: bad input is exit 2 with a message, and no report files") {
    Masks m;
    const std::string report = " --report " + (m.dir / "r.pdf");
    // A missing mask file.
    auto r = run_cli("compare " + m.a + " " + (m.dir / "missing.mask.json") + kFast + report);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("missing.mask.json") != std::string::npos);
    CHECK(m.others() == 0);
    // Rule: one camera per report. A mask for another pinhole size is refused, naming the field.
    pinmask::Mask other = small_mask(5);
    other.camera.pinhole_m = 500e-6;
    const std::string o = m.dir / "other.mask.json";
    pinmask::io::write_mask_file(o, other);
    r = run_cli("compare " + m.a + " " + o + kFast + report);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("pinhole_m") != std::string::npos);
    fs::remove(o);
    CHECK(m.others() == 0);
    // Report formats and folders.
    r = run_cli("compare " + m.a + kFast + "--report " + (m.dir / "r.jpg"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--report") != std::string::npos);
    r = run_cli("compare " + m.a + kFast + "--report " + (m.dir / "no/such/dir/r.pdf"));
    CHECK(r.exit_code == 2);
    // Flags out of range name themselves.
    for (const std::string bad :
         {"--baseline-count 0", "--nsr 0", "--tv-lambda -1", "--prior bogus", "--prior-scenes 0",
          "--tv-iters 0", "--baseline-count 20000", "--photons 1e19", "--read-noise 3"}) {
        r = run_cli("compare " + m.a + kFast + bad + report);
        INFO(bad);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(bad.substr(0, bad.find(' '))) != std::string::npos);
    }
    CHECK(m.others() == 0);
}

// One metric set: the same masks and settings give the same analytic and simulated
// numbers in score and compare (exact equality: both call optimize/metrics/mask_metrics), under the
// Gaussian and the photon model; so compare ranks masks as score does.
TEST_CASE("compare and score print the same analytic and simulated numbers, in the same order") {
    Masks m;
    const std::string c = m.dir / "c.mask.json";
    pinmask::io::write_mask_file(c, small_mask(3, 8, 9));
    const std::string masks = " " + m.a + " " + m.b + " " + c + " ";
    const std::string common = " --scenes letter-R --nsr 0.01 --tv-iters 30 --seed 1 ";
    for (const std::string noise : {"--snr 25", "--photons 2 --read-noise 3"}) {
        INFO(noise);
        const auto s = run_cli("score" + masks + common + noise +
                               " --metrics analytic,wiener,tv --json --quiet");
        const auto k = run_cli("compare" + masks + common + noise + " --json --quiet");
        INFO(s.err << k.err);
        REQUIRE(s.exit_code == 0);
        REQUIRE(k.exit_code == 0);
        const auto js = nlohmann::json::parse(s.out), jc = nlohmann::json::parse(k.out);
        REQUIRE(js["masks"].size() == 3);
        REQUIRE(jc["masks"].size() == 3);
        const std::string key = noise[2] == 's' ? "snr25" : "ph2";
        std::vector<std::pair<double, int>> score_order, compare_order;
        for (int i = 0; i < 3; ++i) {
            const auto &a = js["masks"][i], &b = jc["masks"][i];
            CHECK(a["geometry_hash"] == b["geometry_hash"]);
            for (const std::string metric :
                 {"analytic_wiener_psnr_db_", "analytic_mmse_psnr_db_", "sim_wiener_psnr_db_",
                  "sim_tv_psnr_db_", "sim_wiener_ssim_"}) {
                INFO(metric << key);
                REQUIRE(b.contains(metric + key));
                CHECK(a[metric + key].get<double>() == b[metric + key].get<double>());
            }
            CHECK(b["analytic_wiener_psnr_db"] == b["analytic_wiener_psnr_db_" + key]);
            score_order.push_back({a["sim_wiener_psnr_db_" + key].get<double>(), i});
            compare_order.push_back({b["sim_wiener_psnr_db"].get<double>(), i});
        }
        std::sort(score_order.begin(), score_order.end());
        std::sort(compare_order.begin(), compare_order.end());
        for (int i = 0; i < 3; ++i) CHECK(score_order[i].second == compare_order[i].second);
    }
}

// compare's paired standard error, recomputed from score's per-scene figures of the same masks
// under the same settings (another command's output and this test's own arithmetic).
TEST_CASE("compare: the simulated difference to the first mask is paired over the scenes") {
    Masks m;
    const std::string common =
        " --scenes letter-R,usaf,siemens-star --snr 30 --nsr tuned --seed 1 --tv-iters 5 ";
    const auto k = run_cli("compare " + m.a + " " + m.b + common + "--json --quiet");
    const auto s = run_cli("score " + m.a + " " + m.b + common +
                           "--metrics wiener --tv-lambda 1e-3 --json --quiet");
    INFO(k.err << s.err);
    REQUIRE(k.exit_code == 0);
    REQUIRE(s.exit_code == 0);
    const auto jc = nlohmann::json::parse(k.out), js = nlohmann::json::parse(s.out);
    std::vector<double> d;
    for (const char* scene : {"letter-R", "usaf", "siemens-star"}) {
        const auto at = [&](int i) {
            return js["masks"][i]["per_scene"][scene]["sim_wiener_psnr_db_snr30"].get<double>();
        };
        d.push_back(at(1) - at(0));
    }
    const double mean = (d[0] + d[1] + d[2]) / 3.0;
    double ss = 0.0;
    for (double x : d) ss += (x - mean) * (x - mean);
    const double se = std::sqrt(ss / 2.0) / std::sqrt(3.0);
    const auto& diff = jc["masks"][1]["difference_to_first"]["sim_wiener_psnr_db"];
    CHECK(diff["samples"] == 3);
    CHECK(diff["difference_db"].get<double>() == doctest::Approx(mean).epsilon(1e-12));
    CHECK(diff["standard_error_db"].get<double>() == doctest::Approx(se).epsilon(1e-12));
    CHECK(diff["significant"] == (std::fabs(mean) >= 2.0 * se));
}
