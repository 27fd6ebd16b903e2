// One set of PSNR numbers: search and compare simulate the same default scenes with the same
// settings, so a mask shows one simulated figure in both; every PSNR column says what it is
// computed on (tables, JSON); search's summary states the re-rank rule.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_run.hpp"

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
    CHECK(cj["masks"][0]["wiener_psnr_db"].get<double>() ==
          doctest::Approx(searched).epsilon(1e-12));
    CHECK(cj["settings"]["scenes"] == "letter-R,usaf,siemens-star");

    // Each PSNR column names its basis, in both JSONs and in both tables.
    for (const auto* j : {&sj, &cj}) {
        const auto& cols = (*j)["psnr_columns"];
        CHECK(contains(cols["analytic_wiener_psnr_db"].get<std::string>(), "prior"));
        const std::string sim = j == &sj ? cols["sim_wiener_psnr_db"].get<std::string>()
                                         : cols["wiener_psnr_db"].get<std::string>();
        CHECK(contains(sim, "letter-R,usaf,siemens-star"));
        CHECK(contains(sim, "NSR tuned"));
    }
    const std::string summary = pinmask::test::slurp(std::filesystem::path(out) / "summary.md");
    CHECK(contains(summary,
                   "simulated Wiener PSNR (dB; scenes letter-R+usaf+siemens-star, NSR "
                   "tuned)"));
    CHECK(contains(summary, "analytic Wiener PSNR (dB; closed form, prior"));
    CHECK(contains(summary, "more than the standard error of the per-scene difference (3 scenes)"));
    const auto ct = run_cli("compare " + path);
    CHECK(contains(ct.out, "sim W = simulated on scenes letter-R,usaf,siemens-star"));
}
