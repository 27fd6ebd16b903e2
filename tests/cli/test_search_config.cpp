// search.config.json: what `pinmask search` writes is read back by `--config` (every key, the
// camera included) and repeats the run byte for byte with an evaluation budget; options on the
// command line override the file; bad files are refused naming the key.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors/error.hpp"
#include "io/search_config.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using namespace pinmask::io;
using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

std::string config_with(const std::string& body) {
    return R"({"format": "pinmask-search-config", "version": 1)" +
           (body.empty() ? std::string() : ", " + body) + "}";
}

}  // namespace

TEST_CASE("a minimal configuration sets nothing; every key is read with its type") {
    const SearchConfig empty = parse_search_config(config_with(""));
    CHECK_FALSE(empty.seed);
    CHECK_FALSE(empty.optics);
    CHECK_FALSE(empty.rerank_scenes);

    const SearchConfig c = parse_search_config(config_with(
        R"("strategy": "random", "time": "2min", "evaluations_per_chain": 500, "threads": 3,
           "seed": 18446744073709551615, "top": 4, "grid": 20, "holes": 30, "tiles": 3,
           "min_spacing_cells": 2.5, "keep_out": "border", "pixels_per_cell": 6,
           "kernel_requested": "box", "kernel_resolved": "box", "kernel_path": "",
           "noise": {"model": "gaussian", "snr_db": 35}, "filter": "nsr:0.01",
           "prior": {"family": "natural", "scenes": 4},
           "weights": {"analytic_wiener": 1, "max_sidelobe": 0.5, "sidelobe_energy": 0.25,
                       "min_spectrum": 2},
           "rerank_scenes": ["usaf"], "rerank_tv": false,
           "optics": {"object_distance_m": "inf", "lens_focal_m": 0.1, "sensor_distance_m": 0.05,
                      "wavelength_m": 6e-7, "pixel_pitch_m": 5e-6, "pinhole_m": 2e-4,
                      "sensor_px": [640, 480]})"));
    CHECK(*c.strategy == "random");
    CHECK(*c.time == "2min");
    CHECK(*c.evaluations_per_chain == 500);
    CHECK(*c.threads == 3);
    CHECK(*c.seed == 18446744073709551615ull);
    CHECK(*c.top == 4);
    CHECK(*c.grid == 20);
    CHECK(*c.holes == 30);
    CHECK(*c.tiles == 3);
    CHECK(*c.min_spacing_cells == 2.5);
    CHECK(*c.keep_out == "border");
    CHECK(*c.pixels_per_cell == 6);
    CHECK(*c.kernel == "box");
    CHECK(*c.snr_db == 35.0);
    CHECK(*c.filter == "nsr:0.01");
    CHECK(*c.prior_scenes == 4);
    CHECK(*c.w_max_sidelobe == 0.5);
    CHECK(*c.w_sidelobe_energy == 0.25);
    CHECK(*c.w_min_spectrum == 2.0);
    CHECK(c.rerank_scenes->size() == 1);
    CHECK(*c.rerank_tv == false);
    REQUIRE(c.optics);
    CHECK(std::isinf(c.optics->object_distance_m));
    CHECK(c.optics->sensor_cols == 640);
}

TEST_CASE("bad configurations are refused naming the key and the rule") {
    const std::pair<std::string, std::string> cases[] = {
        {R"({"format": "pinmask-mask", "version": 1})", "not a search config"},
        {R"({"version": 1})", "format"},
        {config_with("").replace(config_with("").find("1}"), 2, "2}"), "version"},
        {config_with(R"("gird": 16)"), "gird: unknown key"},
        {config_with(R"("grid": "16")"), "grid: must be"},
        {config_with(R"("grid": 0)"), "grid: 0 must be >= 1"},
        {config_with(R"("holes": 1.5)"), "holes"},
        {config_with(R"("seed": -1)"), "seed: must be an integer >= 0"},
        {config_with(R"("evaluations_per_chain": -5)"), "evaluations_per_chain"},
        {config_with(R"("strategy": "greedy")"),
         "strategy: 'greedy' is not one of random | anneal"},
        {config_with(R"("time": "11e307h")"), "out of range"},
        {config_with(R"("time": "0s")"), "positive duration"},
        {config_with(R"("min_spacing_cells": -2)"), "min_spacing_cells: must be > 0"},
        {config_with(R"("noise": {"model": "photon"})"), "noise.photons_per_pinhole"},
        {config_with(R"("noise": {"model": "poisson"})"), "noise.model"},
        {config_with(R"("noise": {"photons_per_pinhole": 3})"), "photon model"},
        {config_with(R"("prior": {"family": "galaxies"})"), "prior.family"},
        {config_with(R"("rank_by": "rl")"), "rank_by"},
        {config_with(R"("allow_spectral_zeros": "yes")"), "allow_spectral_zeros"},
        {config_with(R"("noise": {"snr_db": 1e999})"), "number overflow"},
        {config_with(R"("noise": {"snr_db": "30dB"})"), "noise.snr_db: must be"},
        {config_with(R"("prior": {"scenes": 0})"), "prior.scenes"},
        {config_with(R"("weights": {"analytic": 1})"), "weights.analytic: unknown key"},
        {config_with(R"("rerank_scenes": "usaf")"), "rerank_scenes: must be an array"},
        {config_with(R"("rerank_tv": 1)"), "rerank_tv"},
        {config_with(R"("optics": {"wavelength_m": 5e-7})"), "optics.object_distance_m"},
        {config_with(R"("seed": 1, "seed": 2)"), "seed"},
    };
    for (const auto& c : cases) {
        const std::string& text = c.first;
        const std::string& needle = c.second;
        INFO(text);
        std::string message;
        try {
            parse_search_config(text);
        } catch (const InvalidInput& e) {
            message = e.what();
        } catch (const std::exception& e) {
            message = std::string("not InvalidInput: ") + e.what();
        }
        INFO(message);
        CHECK(message.find(needle) != std::string::npos);
        CHECK(message.find("not InvalidInput") == std::string::npos);
    }
    CHECK_THROWS_AS(parse_search_config(std::string(100000, '[')), InvalidInput);
}

TEST_CASE("search --config repeats a run byte for byte, and the command line overrides it") {
    TempDir dir("search-config");
    const std::string a = (dir.path / "a").string(), b = (dir.path / "b").string(),
                      c = (dir.path / "c").string();
    const std::string common =
        "--grid 12 --holes 8 --pixels-per-cell 4 --evals 300 --threads 1 --top 2 "
        "--prior-scenes 2 --rerank-scenes usaf --no-rerank-tv --lens-focal 100mm "
        "--wavelength 600nm";
    const auto first = run_cli("search " + common + " --seed 3 -o '" + a + "'");
    REQUIRE(first.exit_code == 0);
    const auto again = run_cli("search --config '" + a + "/search.config.json' -o '" + b + "'");
    INFO(again.err);
    REQUIRE(again.exit_code == 0);
    CHECK(slurp(a + "/search.config.json") == slurp(b + "/search.config.json"));
    CHECK(slurp(a + "/rank-1.mask.json") == slurp(b + "/rank-1.mask.json"));
    CHECK(slurp(a + "/rank-2.mask.json") == slurp(b + "/rank-2.mask.json"));
    // An --evals run records no time budget, and the rank count it ran on.
    const auto written = nlohmann::json::parse(slurp(a + "/search.config.json"));
    CHECK(written["time"].is_null());
    CHECK(written["evaluations_per_chain"] == 300);
    CHECK(written["ranks"] == 1);
    CHECK(*read_search_config(a + "/search.config.json").ranks == 1);
    CHECK_FALSE(contains(again.err, "not the same search"));
    // A file written on 3 ranks, re-run on 1: said on stderr.
    {
        auto three = written;
        three["ranks"] = 3;
        const std::string path = (dir.path / "three.config.json").string();
        std::ofstream(path) << three.dump(2);
        const auto other =
            run_cli("search --config '" + path + "' -o '" + (dir.path / "d").string() + "'");
        INFO(other.err);
        CHECK(other.exit_code == 0);
        CHECK(contains(other.err, "written by a run on 3 rank(s), this run has 1"));
    }

    // Overrides: the seed, the budget (a --time replaces the file's evaluations) and one camera
    // field; everything else, the rest of the camera included, from the file.
    const auto varied =
        run_cli("search --config '" + a +
                "/search.config.json' --seed 4 --time 1s --pinhole 400um -o '" + c + "'");
    INFO(varied.err);
    REQUIRE(varied.exit_code == 0);
    const SearchConfig v = read_search_config(c + "/search.config.json");
    CHECK(*v.seed == 4);
    CHECK(*v.time == "1s");
    CHECK(*v.evaluations_per_chain == 0);
    CHECK(*v.grid == 12);
    CHECK(*v.rerank_tv == false);
    CHECK(v.optics->pinhole_m == doctest::Approx(400e-6));
    CHECK(v.optics->lens_focal_m == doctest::Approx(0.1));
    CHECK(v.optics->wavelength_m == doctest::Approx(600e-9));
}

TEST_CASE("search --config repeats a photon-model run with a text prior byte for byte") {
    TempDir dir("search-config-photon");
    const std::string a = (dir.path / "a").string(), b = (dir.path / "b").string();
    const auto first = run_cli(
        "search --grid 8 --holes 5 --pixels-per-cell 4 --tiles 1 --evals 100 --threads 1 --top 2 "
        "--prior text --prior-scenes 2 --photons 3 --read-noise 3 --dark-current 1 "
        "--rerank-scenes usaf --no-rerank-tv --quiet -o '" +
        a + "'");
    INFO(first.err);
    REQUIRE(first.exit_code == 0);
    const SearchConfig c = read_search_config(a + "/search.config.json");
    CHECK(*c.photons == 3.0);
    CHECK(*c.read_noise == 3.0);
    CHECK(*c.dark_current == 1.0);
    CHECK(*c.prior_family == "text");
    const auto again =
        run_cli("search --config '" + a + "/search.config.json' --quiet -o '" + b + "'");
    INFO(again.err);
    REQUIRE(again.exit_code == 0);
    for (const char* f : {"search.config.json", "rank-1.mask.json", "run-log.csv", "summary.md"})
        CHECK(slurp(a + "/" + f) == slurp(b + "/" + f));
}
