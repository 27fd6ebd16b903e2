// `pinmask bench error-time` end to end: a small mask (8 x 8 cells of 4 pixels, a 32 x 32 period)
// with --quick, and the paper preset checked against `pinmask generate --family paper --seed 1`.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/image/image_io.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

TEST_CASE("bench error-time --quick writes CSV, Markdown, plots and config; --json summarises") {
    TempDir dir("error-time");
    const std::string mask = dir / "m.mask.json", out = dir / "out";
    REQUIRE(run_cli("generate --family random --grid 8 --holes 5 --pixels-per-cell 4 --seed 1 -o " +
                    mask)
                .exit_code == 0);
    const auto r = run_cli("bench error-time " + mask +
                           " --quick --scenes letter-R,natural --snr 20,30 --json -o " + out);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    std::set<std::string> decoders;
    for (const auto& b : j["best"]) decoders.insert(b["decoder"].get<std::string>());
    CHECK(decoders ==
          std::set<std::string>{"wiener", "tikhonov", "tv-l2", "tvqc", "richardson-lucy"});
    CHECK(j["best"].size() == 10);  // 5 decoders x 2 SNRs
    // --quick: 2 NSR + 1 Tikhonov + 3 x 3 iteration counts per SNR.
    CHECK(j["points"].size() == 2 * 12);
    for (const char* f : {"error_time.csv", "error_time_points.csv", "error_time.md",
                          "error_time.config.json", "error_time_snr20.svg", "error_time_snr20.png",
                          "error_time_snr30.svg", "error_time_snr30.png"}) {
        INFO(f);
        CHECK(fs::exists(fs::path(out) / f));
    }
    const pinmask::LoadedImage png = pinmask::read_image(fs::path(out) / "error_time_snr30.png");
    CHECK(png.image.cols() > png.image.rows());
    const std::string md = slurp(fs::path(out) / "error_time.md");
    CHECK(md.find("### SNR 20 dB") != std::string::npos);
    CHECK(md.find("| tvqc |") != std::string::npos);
    const auto cfg = nlohmann::json::parse(slurp(fs::path(out) / "error_time.config.json"));
    CHECK(cfg["quick"] == true);
    CHECK(cfg["period_px"] == 32);
}

TEST_CASE("bench error-time: the paper preset is the generated paper mask of seed 1") {
    TempDir dir("error-time-preset");
    const std::string mask = dir / "paper.mask.json", out = dir / "out";
    REQUIRE(run_cli("generate --family paper --seed 1 -o " + mask).exit_code == 0);
    const auto g =
        run_cli("generate --family paper --seed 1 --json -o " + (dir / "again.mask.json"));
    REQUIRE(g.exit_code == 0);
    const std::string hash = nlohmann::json::parse(g.out)["geometry_hash"];
    // A trailing slash names the directory itself.
    const auto r =
        run_cli("bench error-time --preset paper --quick --scenes point -o " + out + "/");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("| wiener |") != std::string::npos);  // the Markdown table on stdout
    const auto cfg = nlohmann::json::parse(slurp(fs::path(out) / "error_time.config.json"));
    CHECK(cfg["geometry_hash"] == hash);
    CHECK(cfg["period_px"] == 128);
}

TEST_CASE("bench error-time refuses bad requests with exit 2 and writes nothing") {
    TempDir dir("error-time-bad");
    const std::string mask = dir / "m.mask.json", out = dir / "out";
    REQUIRE(run_cli("generate --family random --grid 8 --holes 5 --pixels-per-cell 4 -o " + mask)
                .exit_code == 0);
    for (const std::string& args :
         {mask + " --preset paper",  // both a mask and a preset
          mask + " --iters 0",       // counts are >= 1
          mask + " --iters 2.5",     // and integers
          mask + " --nsr -1",        // NSR >= 0
          mask + " --scenes usaf,,natural", mask + " --tv-lambda 0", (dir / "missing.mask.json")}) {
        INFO(args);
        CHECK(run_cli("bench error-time " + args + " -o " + out).exit_code == 2);
        CHECK(!fs::exists(out));
    }
}
