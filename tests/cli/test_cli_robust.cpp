// Fabrication robustness end to end: `--robust` in score, compare and search,
// `search --objective robust`, hostile values exit 2 naming the key, and deterministic outputs.
// Small geometries (8 x 8 cells of 4 pixels) keep every run short.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli/generated_masks.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

constexpr const char* kErrors = " --robust size=44um,jitter=20um,missing=0.05 ";
constexpr const char* kSearch =
    " --grid 8 --holes 5 --pixels-per-cell 4 --tiles 1 --prior-scenes 2 --threads 1 --top 2 "
    "--seed 4 --evals 300 --rerank-scenes letter-R --no-rerank-tv --quiet ";

struct RobustMasks : pinmask::test::GeneratedMasks {
    RobustMasks() : GeneratedMasks("robust") {}
};

}  // namespace

TEST_CASE("score --robust: robust figures beside the nominal ones; no errors give them exactly") {
    RobustMasks m;
    auto r =
        run_cli("score " + m.a + " " + m.b + " --metrics analytic --snr 30" + kErrors + "--json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    auto j = nlohmann::json::parse(r.out);
    for (const auto& row : j["masks"]) {
        const double nominal = row["analytic_wiener_psnr_db_snr30"].get<double>();
        const double robust = row["analytic_robust_wiener_psnr_db_snr30"].get<double>();
        CHECK(robust < nominal);
        CHECK(row["analytic_robust_wiener_loss_db_snr30"].get<double>() ==
              doctest::Approx(nominal - robust));
    }
    CHECK(j["settings"]["robust"].get<std::string>().find("size +-44 um") != std::string::npos);
    // The table has the R column and says what it is.
    r = run_cli("score " + m.a + " --metrics analytic --snr 30" + kErrors);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("Rsnr30") != std::string::npos);
    CHECK(r.out.find("fabrication errors") != std::string::npos);
    // Zero errors: the robust figure is the nominal one, bit for bit.
    r = run_cli("score " + m.a + " --metrics analytic --snr 30 --robust size=0,missing=0 --json");
    REQUIRE(r.exit_code == 0);
    j = nlohmann::json::parse(r.out);
    CHECK(!j["masks"][0].contains("analytic_robust_wiener_psnr_db_snr30"));  // no errors: no column
    r = run_cli("score " + m.a + " --metrics analytic --snr 30 --robust jitter=1e-17 --json");
    REQUIRE(r.exit_code == 0);
    j = nlohmann::json::parse(r.out);
    CHECK(j["masks"][0]["analytic_robust_wiener_psnr_db_snr30"].get<double>() ==
          doctest::Approx(j["masks"][0]["analytic_wiener_psnr_db_snr30"].get<double>())
              .epsilon(1e-9));
}

TEST_CASE("hostile --robust values exit 2 naming the key, in score, compare and search") {
    RobustMasks m;
    const std::pair<const char*, const char*> bad[] = {{"size=-5um", "--robust size"},
                                                       {"jitter=nan", "--robust jitter"},
                                                       {"missing=1", "--robust missing"},
                                                       {"missing=-0.5", "--robust missing"},
                                                       {"jitter=1mm", "--robust jitter"},
                                                       {"size=440um", "--robust size"},
                                                       {"colour=3", "colour"},
                                                       {"size=1um,size=2um", "--robust size"},
                                                       {"size", "--robust"},
                                                       {"jitter=2parsecs", "--robust jitter"},
                                                       {"missing=1e400", "--robust missing"},
                                                       {"size=1um,,jitter=1um", "--robust"}};
    for (const auto& item : bad) {
        // Named copies: clang-14 refuses structured bindings in INFO.
        const std::string value = item.first, key = item.second;
        const std::string spec = " --robust '" + value + "' ";
        INFO(value);
        auto r = run_cli("score " + m.a + " --metrics analytic" + spec);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(key) != std::string::npos);
        const std::string report = m.dir / "r.pdf";
        r = run_cli("compare " + m.a + " --scenes letter-R --tv-iters 5" + spec + "--report " +
                    report);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(key) != std::string::npos);
        CHECK(!fs::exists(report));
        CHECK(!fs::exists(m.dir / "r.config.json"));
        r = run_cli(std::string("search") + kSearch + spec + "-o " + (m.dir / "s"));
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(key) != std::string::npos);
        CHECK(!fs::exists(m.dir / "s"));
    }
    // --objective robust needs errors, and only nominal|robust exist.
    auto r = run_cli(std::string("search") + kSearch + "--objective robust -o " + (m.dir / "s"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--objective") != std::string::npos);
    r = run_cli(std::string("search") + kSearch + "--objective best" + kErrors + "-o " +
                (m.dir / "s"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--objective") != std::string::npos);
}

TEST_CASE("compare --robust: the robust column is score's number; report written") {
    RobustMasks m;
    const std::string report = m.dir / "r.svg";
    auto r = run_cli("compare " + m.a + " " + m.b +
                     " --scenes letter-R --tv-iters 5 --snr 30 --nsr 0.01" + kErrors + "--json" +
                     " --report " + report);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto jc = nlohmann::json::parse(r.out);
    const auto s = run_cli("score " + m.a + " " + m.b + " --metrics analytic --snr 30 --nsr 0.01" +
                           kErrors + "--json");
    REQUIRE(s.exit_code == 0);
    const auto js = nlohmann::json::parse(s.out);
    for (int i = 0; i < 2; ++i) {
        CHECK(jc["masks"][i]["analytic_robust_wiener_psnr_db_snr30"].get<double>() ==
              js["masks"][i]["analytic_robust_wiener_psnr_db_snr30"].get<double>());
    }
    CHECK(fs::exists(m.dir / "r-1.svg"));
    const auto t = run_cli("compare " + m.a + " --scenes letter-R --tv-iters 5 --snr 30" + kErrors);
    REQUIRE(t.exit_code == 0);
    CHECK(t.out.find("robust W") != std::string::npos);
}

TEST_CASE("search --objective robust: recorded, repeatable byte for byte, and via --config") {
    TempDir dir("robust-search");
    const std::string args = std::string("search") + kSearch + kErrors + "--objective robust ";
    auto r = run_cli(args + "--json -o " + (dir / "a"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    const double robust = j["ranked"][0]["analytic_robust_mmse_psnr_db"].get<double>();
    CHECK(robust < j["ranked"][0]["analytic_mmse_psnr_db"].get<double>());
    CHECK(j["ranked"][0]["objective"].get<double>() == doctest::Approx(-robust));
    const auto config = nlohmann::json::parse(slurp(dir.path / "a" / "search.config.json"));
    CHECK(config["objective"] == "robust");
    CHECK(config["robust"] == "size=44um,jitter=20um,missing=0.05");
    CHECK(slurp(dir.path / "a" / "summary.md").find("expected under the --robust") !=
          std::string::npos);
    // Same seed, same bytes.
    REQUIRE(run_cli(args + "-o " + (dir / "b")).exit_code == 0);
    for (const char* f : {"rank-1.mask.json", "rank-2.mask.json", "summary.md", "run-log.csv"})
        CHECK(slurp(dir.path / "a" / f) == slurp(dir.path / "b" / f));
    // --config repeats it.
    REQUIRE(
        run_cli("search --config " + (dir / "a/search.config.json") + " --quiet -o " + (dir / "c"))
            .exit_code == 0);
    CHECK(slurp(dir.path / "a" / "rank-1.mask.json") == slurp(dir.path / "c" / "rank-1.mask.json"));
    // The robust mask scores the same robust figure in score (optimal filter = the search's).
    const auto nominal =
        run_cli(std::string("search") + kSearch + kErrors + "--json -o " + (dir / "n"));
    REQUIRE(nominal.exit_code == 0);
    const auto jn = nlohmann::json::parse(nominal.out);
    CHECK(jn["ranked"][0].contains("analytic_robust_mmse_psnr_db"));  // reported beside the nominal
}
