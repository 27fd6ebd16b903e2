// One set of PSNR numbers: search and compare simulate the same default scenes with the same
// settings, so a mask shows one simulated figure in both; every PSNR column says what it is
// computed on (tables, JSON); search's summary states the re-rank rule.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_run.hpp"
#include "tests/support/external_tool.hpp"

using pinmask::test::run_cli;
using pinmask::test::TempDir;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("a searched mask shows one simulated Wiener PSNR in search and in compare") {
    TempDir dir("psnr-one-figure");
    const std::string out = (dir.path / "run").string();
    // Default re-rank scenes, noise (30 dB) and seed (1) on both sides.
    const auto s = run_cli(
        "search --grid 8 --pixels-per-cell 4 --tiles 1 --holes 5 --prior-scenes 2 --threads 1 "
        "--top 3 --evals 300 --quiet --json -o " +
        out);
    INFO(s.err);
    REQUIRE(s.exit_code == 0);
    const auto sj = nlohmann::json::parse(s.out);
    REQUIRE(sj["ranked"].size() >= 1);
    const auto& top = sj["ranked"][0];
    const std::string path = top["path"].get<std::string>();
    const double searched = top["sim_wiener_psnr_db"].get<double>();

    const auto c = run_cli("compare " + path + " --json");
    INFO(c.err);
    REQUIRE(c.exit_code == 0);
    const auto cj = nlohmann::json::parse(c.out);
    CHECK(cj["masks"][0]["sim_wiener_psnr_db"].get<double>() ==
          doctest::Approx(searched).epsilon(1e-12));
    CHECK(cj["settings"]["scenes"] == "letter-R,usaf,siemens-star");

    // Each PSNR column names its basis, in both JSONs and in both tables.
    for (const auto* j : {&sj, &cj}) {
        const auto& cols = (*j)["psnr_columns"];
        CHECK(contains(cols["analytic_wiener_psnr_db"].get<std::string>(), "prior"));
        CHECK(contains(cols["analytic_mmse_psnr_db"].get<std::string>(), "optimal (MMSE)"));
        const std::string sim = cols["sim_wiener_psnr_db"].get<std::string>();
        CHECK(contains(sim, "letter-R,usaf,siemens-star"));
        CHECK(contains(sim, "NSR tuned"));
    }
    const std::string summary = pinmask::test::slurp(std::filesystem::path(out) / "summary.md");
    CHECK(contains(summary,
                   "simulated Wiener PSNR (dB; sim_wiener_psnr_db, scenes "
                   "letter-R+usaf+siemens-star, NSR tuned)"));
    CHECK(contains(summary, "analytic MMSE PSNR (dB; analytic_mmse_psnr_db, closed form, prior"));
    CHECK(contains(summary, "more than the standard error of the per-scene difference (3 scenes)"));
    const auto ct = run_cli("compare " + path);
    CHECK(contains(ct.out, "sim W = simulated on scenes letter-R,usaf,siemens-star"));
}

// The figure search optimises is the figure compare leads with, and both compute it alike: for
// the same mask, camera, prior and noise they agree to 1e-9 dB. Under a Gaussian SNR search
// optimises the MMSE figure (optimal filter), under the photon model the Wiener figure at the
// NSR tuned per mask; two cameras (the paper's at a small grid and a shorter lens).
TEST_CASE("search's optimised figure and compare's lead figure agree to 1e-9 for the same mask") {
    constexpr double kSameFigureDb = 1e-9;
    struct Case {
        const char* name;
        std::string camera, noise;
        const char* figure;
    };
    const Case cases[] = {
        {"paper camera, SNR 30 dB", "", "--snr 30", "analytic_mmse_psnr_db"},
        {"paper camera, 5 e- per pinhole", "", "--photons 5", "analytic_wiener_psnr_db"},
        {"35 mm lens, sensor 30 mm, SNR 25 dB",
         "--lens-focal 35mm --sensor-distance 30mm --pinhole 150um ", "--snr 25",
         "analytic_mmse_psnr_db"},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        TempDir dir("psnr-agree");
        const std::string out = (dir.path / "run").string();
        const auto s = run_cli(
            "search --grid 8 --pixels-per-cell 4 --tiles 1 --holes 5 --prior-scenes 2 "
            "--threads 1 --top 2 --evals 200 --no-rerank --quiet --json " +
            c.camera + c.noise + " -o " + out);
        INFO(s.err);
        REQUIRE(s.exit_code == 0);
        const auto sj = nlohmann::json::parse(s.out);
        CHECK(sj["objective_figure"] == c.figure);
        const auto& top = sj["ranked"][0];
        REQUIRE(top.contains(c.figure));
        // The camera comes with the mask file; the noise and prior are compare's own flags.
        const auto k = run_cli("compare " + top["path"].get<std::string>() +
                               " --prior-scenes 2 --json --quiet " + c.noise);
        INFO(k.err);
        REQUIRE(k.exit_code == 0);
        const auto cj = nlohmann::json::parse(k.out);
        CHECK(cj["lead_figure"]["name"] == c.figure);
        CHECK(contains(cj["lead_figure"]["reason"].get<std::string>(), "search optimised"));
        CHECK_FALSE(cj["lead_figure"].contains("mismatch"));
        const double searched = top[c.figure].get<double>();
        const double compared = cj["masks"][0][c.figure].get<double>();
        CHECK(std::fabs(searched - compared) <= kSameFigureDb);
        // The optimal filter's figure is reported by both whatever the search's filter.
        CHECK(std::fabs(top["analytic_mmse_psnr_db"].get<double>() -
                        cj["masks"][0]["analytic_mmse_psnr_db"].get<double>()) <= kSameFigureDb);
    }
}

// compare under other settings than the search's says that its lead figure differs from the
// one the file records.
TEST_CASE("compare says when its lead figure differs from the search's recorded one") {
    TempDir dir("psnr-mismatch");
    const std::string out = (dir.path / "run").string();
    const auto s = run_cli(
        "search --grid 8 --pixels-per-cell 4 --tiles 1 --holes 5 --prior-scenes 2 --threads 1 "
        "--top 1 --evals 100 --no-rerank --quiet --json -o " +
        out);
    REQUIRE(s.exit_code == 0);
    const auto sj = nlohmann::json::parse(s.out);
    const auto k = run_cli("compare " + sj["ranked"][0]["path"].get<std::string>() +
                           " --prior-scenes 3 --snr 30 --json --quiet");
    REQUIRE(k.exit_code == 0);
    const auto cj = nlohmann::json::parse(k.out);
    REQUIRE(cj["lead_figure"].contains("mismatch"));
    CHECK(contains(cj["lead_figure"]["mismatch"].get<std::string>(), "records"));
}

// scripts/demo's chain, small: search, then compare the rank-1 mask with --baselines. The report
// states the searched mask's gain over the random median on the figure the search optimised,
// with the median's standard error, or that there is no significant gain.
TEST_CASE("the demo's report states the searched mask's gain over the random median with its SE") {
    TempDir dir("psnr-demo");
    const std::string out = (dir.path / "search").string();
    const auto s = run_cli(
        "search --preset paper --grid 8 --pixels-per-cell 4 --tiles 1 --holes 5 --prior-scenes 2 "
        "--threads 1 --top 1 --evals 300 --no-rerank --quiet --json -o " +
        out);
    INFO(s.err);
    REQUIRE(s.exit_code == 0);
    const auto sj = nlohmann::json::parse(s.out);
    const std::string report = (dir.path / "report.pdf").string();
    const auto c = run_cli("compare " + sj["ranked"][0]["path"].get<std::string>() +
                           " --baselines --baseline-count 21 --snr 30 --prior-scenes 2 --scenes "
                           "letter-R --tv-iters 5 --quiet --json --report " +
                           report);
    INFO(c.err);
    REQUIRE(c.exit_code == 0);
    const auto cj = nlohmann::json::parse(c.out);
    const std::string figure = sj["objective_figure"];
    CHECK(cj["lead_figure"]["name"] == figure);
    const auto& rnd = cj["baselines"]["random"];
    CHECK(rnd["ranked_by"] == figure);
    const auto& gain = rnd["first_mask_gain"];
    const double first = cj["masks"][0][figure].get<double>();
    CHECK(gain["difference_db"].get<double>() ==
          doctest::Approx(first - rnd["median_" + figure].get<double>()).epsilon(1e-12));
    const double se = gain["standard_error_db"].get<double>();
    CHECK(se > 0.0);
    CHECK(gain["significant"] == (std::fabs(gain["difference_db"].get<double>()) >= 2.0 * se));
    const std::string text = gain["text"];
    CHECK(contains(text, "standard error"));
    CHECK((contains(text, "A significant gain") || contains(text, "No significant gain") ||
           contains(text, "A significant LOSS")));
    // The same sentence in the report's configuration, on its first page (read back by poppler
    // where installed: the pages draw their text as glyphs) and after the command's table.
    const auto config =
        nlohmann::json::parse(pinmask::test::slurp(dir.path / "report.config.json"));
    CHECK(config["baselines"]["random"]["first_mask_gain"]["text"] == text);
    if (pinmask::test::have_tool("command -v pdftotext")) {
        auto [rc, page] = pinmask::test::run_tool("pdftotext -l 1 " + report + " -", dir);
        REQUIRE(rc == 0);
        for (char& ch : page)
            if (ch == '\n') ch = ' ';  // the report wraps its lines
        CHECK(contains(page, "Gain of"));
        CHECK(contains(page, "standard error"));
        CHECK(contains(page, text.substr(text.rfind(". ") + 2, 20)));  // the verdict
    } else {
        MESSAGE("report text not read back: poppler-utils (pdftotext) is not installed");
    }
    const auto t = run_cli("compare " + sj["ranked"][0]["path"].get<std::string>() +
                           " --baselines --baseline-count 21 --snr 30 --prior-scenes 2 --scenes "
                           "letter-R --tv-iters 5 --quiet");
    CHECK(contains(t.out, "Leading with " + figure));
    CHECK(contains(t.out, "Gain of"));
}
