// `pinmask search` end to end: the photon objective, spectral zeros, the time
// budget with re-ranking, --rank-by, and --evals 0. Small geometries keep each run under a few
// seconds.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

constexpr const char* kSmall =
    " --grid 8 --holes 5 --pixels-per-cell 4 --tiles 1 --prior-scenes 2 --threads 1 --top 3 "
    "--seed 2 --rerank-scenes letter-R --quiet ";

}  // namespace

TEST_CASE("search --photons: the photon model is the objective and is recorded") {
    TempDir dir("search-photons");
    const auto r = run_cli(std::string("search") + kSmall +
                           "--evals 200 --photons 3 --read-noise 3 --json -o " + (dir / "run"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto config = nlohmann::json::parse(slurp(dir.path / "run" / "search.config.json"));
    CHECK(config["noise"]["model"] == "photon");
    CHECK(config["noise"]["photons_per_pinhole"] == 3.0);
    CHECK(config["noise"]["read_noise_e"] == 3.0);
    // The objective's analytic PSNR is the one score computes for the same photon level,
    // prior and filter: under --photons the search's --filter auto is the tuned NSR.
    const auto j = nlohmann::json::parse(r.out);
    const double objective_psnr = j["ranked"][0]["analytic_wiener_psnr_db"].get<double>();
    const auto s =
        run_cli("score " + (dir.path / "run" / "rank-1.mask.json").string() +
                " --metrics analytic --photons 3 --read-noise 3 --prior-scenes 2 --nsr tuned "
                "--json");
    REQUIRE(s.exit_code == 0);
    const auto js = nlohmann::json::parse(s.out);
    CHECK(js["masks"][0]["analytic_wiener_psnr_db_ph3"].get<double>() ==
          doctest::Approx(objective_psnr).epsilon(1e-9));
    // Lists are for score and compare: search optimises one level.
    const auto bad =
        run_cli(std::string("search") + kSmall + "--evals 10 --photons 3,30 -o " + (dir / "bad"));
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("one noise level") != std::string::npos);
}

// On a 4 x 4 torus every two-pinhole pattern has P^(k) = 1 + w^(k . d) = 0 for some k: the
// search must refuse all of them unless --allow-spectral-zeros, and then flag every result.
TEST_CASE("search never returns an unflagged spectral zero") {
    TempDir dir("search-zeros");
    const std::string args =
        " --grid 4 --holes 2 --pixels-per-cell 4 --tiles 1 --prior-scenes 2 --threads 1 --top 2 "
        "--evals 50 --no-rerank --quiet -o ";
    auto r = run_cli("search" + args + (dir / "a"));
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("spectral zero") != std::string::npos);
    CHECK(r.err.find("--allow-spectral-zeros") != std::string::npos);
    CHECK(!fs::exists(dir.path / "a" / "rank-1.mask.json"));
    r = run_cli("search" + args + (dir / "b") + " --allow-spectral-zeros");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(slurp(dir.path / "b" / "summary.md").find("WARNING: rank 1: spectral zero") !=
          std::string::npos);
    // Score agrees: the result has a spectral zero, with its frequency.
    const auto s = run_cli("score " + (dir.path / "b" / "rank-1.mask.json").string() +
                           " --metrics spectrum --json");
    REQUIRE(s.exit_code == 0);
    CHECK(nlohmann::json::parse(s.out)["masks"][0]["spectral_zero"]["frequency"].size() == 2);
    // A normal search: no result has a spectral zero (score says null for each).
    r = run_cli(std::string("search") + kSmall + "--evals 300 --no-rerank -o " + (dir / "c"));
    REQUIRE(r.exit_code == 0);
    for (int i = 1; i <= 3; ++i) {
        const auto t = run_cli(
            "score " + (dir.path / "c" / ("rank-" + std::to_string(i) + ".mask.json")).string() +
            " --metrics spectrum --json");
        REQUIRE(t.exit_code == 0);
        CHECK(nlohmann::json::parse(t.out)["masks"][0]["spectral_zero"].is_null());
    }
}

// The budget covers the whole run, re-ranking included; the summary reports planned vs used.
// The bound is the required T + 10 % plus a generous allowance for a loaded or sanitized machine
// (the test checks the accounting, not the machine's speed).
TEST_CASE("search --time: planned vs used in the summary, re-ranking inside the budget") {
    TempDir dir("search-time");
    const bool sanitized = std::getenv("PINMASK_SANITIZED") != nullptr;
    const double budget_s = sanitized ? 4.0 : 2.0;
    const auto r =
        run_cli(std::string("search") + kSmall + "--time " +
                std::to_string(static_cast<int>(budget_s)) + "s --json -o " + (dir / "run"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["stop_reason"] == "time budget");
    CHECK(j["planned_s"].get<double>() == budget_s);
    const double used = j["used_s"].get<double>();
    constexpr double kGenerousAllowance_s = 2.0;
    CHECK(used <= 1.10 * budget_s + kGenerousAllowance_s);
    CHECK(j["reranked"].get<int>() >= 1);
    CHECK(used >= j["search_s"].get<double>() + j["rerank_s"].get<double>());
    const std::string summary = slurp(dir.path / "run" / "summary.md");
    CHECK(summary.find("Time: planned") != std::string::npos);
}

TEST_CASE("search --rank-by tv: TV decides the order; --evals 0 and --rank-by bogus refused") {
    TempDir dir("search-rank");
    auto r = run_cli(std::string("search") + kSmall + "--evals 100 --rank-by tv --json -o " +
                     (dir / "run"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["ranked"].size() == 3);
    for (std::size_t i = 0; i + 1 < j["ranked"].size(); ++i) {
        CHECK(j["ranked"][i]["sim_tv_psnr_db"].get<double>() >=
              j["ranked"][i + 1]["sim_tv_psnr_db"].get<double>());
        CHECK(j["ranked"][i].contains("sim_tv_lambda"));
    }
    r = run_cli(std::string("search") + kSmall + "--evals 0 -o " + (dir / "zero"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--evals") != std::string::npos);
    CHECK(!fs::exists(dir.path / "zero"));
    r = run_cli(std::string("search") + kSmall + "--evals 10 --rank-by bogus -o " + (dir / "x"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--rank-by") != std::string::npos);
}

TEST_CASE("search --explain names the prior's irrelevant frequencies and what was skipped") {
    TempDir dir("search-explain");
    const auto r = run_cli(std::string("search") + kSmall +
                           "--evals 20 --prior text --no-rerank --explain -o " + (dir / "run"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("explain: prior text") != std::string::npos);
    CHECK(r.err.find("frequencies carry < 1e-6") != std::string::npos);
    CHECK(r.err.find("Skipped:") != std::string::npos);
}

TEST_CASE("search --holes A..B: best mask per K, table and plot; bad ranges name --holes") {
    TempDir dir("search-holes");
    const std::string args =
        " --grid 8 --pixels-per-cell 4 --tiles 1 --prior-scenes 2 --threads 1 --top 2 --seed 3 "
        "--evals 400 --no-rerank --quiet --photons 3 --read-noise 3 ";
    const auto r = run_cli("search" + args + "--holes 3..8 --json -o " + (dir / "run"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const fs::path run = dir.path / "run";
    for (const char* f : {"holes.csv", "holes.svg", "holes.png"}) CHECK(fs::exists(run / f));
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["best_per_holes"].is_array());
    int previous = 0;
    for (const auto& row : j["best_per_holes"]) {
        const int k = row["holes"].template get<int>();
        CHECK(k >= 3);
        CHECK(k <= 8);
        CHECK(k > previous);  // ascending, one row per K
        previous = k;
        // The per-K mask file holds K pinholes and the predicted PSNR the table shows.
        const auto mask =
            nlohmann::json::parse(slurp(run / ("best-K" + std::to_string(k) + ".mask.json")));
        CHECK(mask.dump().find("analytic_wiener_psnr_db") != std::string::npos);
        // The bound on any K-pinhole pattern (optimize/search/objective_bound) is above the best
        // found, on the figure it bounds (the optimal filter's), and that filter beats the
        // searched one (Wiener at the tuned NSR under --photons).
        CHECK(row["upper_bound_analytic_mmse_psnr_db"].template get<double>() >=
              row["analytic_mmse_psnr_db"].template get<double>());
        CHECK(row["analytic_mmse_psnr_db"].template get<double>() >=
              row["analytic_wiener_psnr_db"].template get<double>());
    }
    CHECK(j["best_per_holes"].size() >= 3);
    const std::string csv = slurp(run / "holes.csv");
    CHECK(csv.rfind("holes,light_gain,objective,analytic_wiener_psnr_db", 0) == 0);
    CHECK(csv.substr(0, csv.find('\n')).find(",upper_bound_analytic_mmse_psnr_db") !=
          std::string::npos);
    CHECK(slurp(run / "summary.md").find("Best mask per pinhole count") != std::string::npos);
    CHECK(slurp(run / "summary.md").find("Best possible for") != std::string::npos);
    const auto config = nlohmann::json::parse(slurp(run / "search.config.json"));
    CHECK(config["holes"] == 3);
    CHECK(config["max_holes"] == 8);
    // Same seed and --evals: byte-identical table and plot.
    const auto again = run_cli("search" + args + "--holes 3..8 -o " + (dir / "again"));
    REQUIRE(again.exit_code == 0);
    CHECK(slurp(dir.path / "again" / "holes.csv") == csv);
    CHECK(slurp(dir.path / "again" / "holes.svg") == slurp(run / "holes.svg"));
    // --config repeats the range.
    const auto from_config = run_cli("search --config " + (run / "search.config.json").string() +
                                     " --quiet -o " + (dir / "cfg"));
    REQUIRE(from_config.exit_code == 0);
    CHECK(slurp(dir.path / "cfg" / "holes.csv") == csv);
    // A single K keeps today's outputs: no per-K table.
    const auto single = run_cli("search" + args + "--holes 5 -o " + (dir / "single"));
    REQUIRE(single.exit_code == 0);
    CHECK_FALSE(fs::exists(dir.path / "single" / "holes.csv"));
    // Bad ranges: exit 2, the message names --holes, nothing written.
    for (const char* bad :
         {"8..3", "0..5", "3..", "..5", "3..x", "3..100", "nan", "99999999999..3"}) {
        const auto b = run_cli("search" + args + "--holes " + bad + " -o " + (dir / "bad"));
        INFO(bad << ": " << b.err);
        CHECK(b.exit_code == 2);
        CHECK(b.err.find("--holes") != std::string::npos);
        CHECK_FALSE(fs::exists(dir.path / "bad"));
    }
}
