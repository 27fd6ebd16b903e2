// io/sweep_config: grid and list expansion (order, values, the base kept), and refusal of bad
// sweep files naming the key (unknown option, empty grid, incompatible values).
#include <doctest/doctest.h>

#include <string>

#include "core/errors/error.hpp"
#include "io/sweep_config.hpp"

using namespace pinmask;

namespace {

const std::string kBase =
    R"("base": {"grid": 8, "evaluations_per_chain": 50, "rerank_scenes": [],
                "noise": {"model": "photon", "photons_per_pinhole": 100}})";

std::string sweep(const std::string& body, const std::string& base = kBase) {
    return R"({"format": "pinmask-sweep", "version": 1, )" + base + ", " + body + "}";
}

// The message of the refusal, or "accepted".
std::string refusal(const std::string& text) {
    try {
        io::parse_sweep_config(text);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "accepted";
}

bool has(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("a grid is the product of its keys, alphabetical, the last varying fastest") {
    const io::SweepConfig c = io::parse_sweep_config(
        sweep(R"("grid": {"noise.photons_per_pinhole": [10, 1000], "holes": [3, 4, 5]})"));
    REQUIRE(c.keys == std::vector<std::string>{"holes", "noise.photons_per_pinhole"});
    REQUIRE(c.points.size() == 6);
    const int holes[] = {3, 3, 4, 4, 5, 5};
    const double photons[] = {10, 1000, 10, 1000, 10, 1000};
    for (std::size_t i = 0; i < 6; ++i) {
        CAPTURE(i);
        const io::SearchConfig& s = c.points[i].config;
        CHECK(s.holes == holes[i]);
        CHECK(s.photons == photons[i]);
        CHECK(s.grid == 8);                    // from the base
        CHECK(s.evaluations_per_chain == 50);  // from the base
        CHECK(s.threads == 1);                 // the sweep's default
        REQUIRE(c.points[i].values.size() == 2);
        CHECK(c.points[i].values[0].number == double(holes[i]));
        CHECK(c.points[i].values[1].text == (photons[i] == 10 ? "10" : "1000"));
    }
}

TEST_CASE("a list of points: keys are the union, a key a point leaves out is the base's") {
    const io::SweepConfig c = io::parse_sweep_config(
        sweep(R"("points": [{"holes": 3}, {"seed": 7, "strategy": "random"}])"));
    REQUIRE(c.keys == std::vector<std::string>{"holes", "seed", "strategy"});
    REQUIRE(c.points.size() == 2);
    CHECK(c.points[0].config.holes == 3);
    CHECK(!c.points[0].config.seed);
    CHECK(c.points[0].values[1].text == "-");
    CHECK(c.points[1].config.seed == 7u);
    CHECK(c.points[1].config.strategy == "random");
    CHECK(c.points[1].values[2].text == "random");
    CHECK(!c.points[1].values[2].number);
}

TEST_CASE("bad sweep files are refused naming the key") {
    // Unknown option: at the top, in the grid, in a list point, inside a nested search object.
    CHECK(has(refusal(sweep(R"("grid": {"holes": [3]}, "extra": 1)")), "extra: unknown key"));
    CHECK(has(refusal(sweep(R"("grid": {"holez": [3, 4]})")), "holez: unknown key"));
    CHECK(has(refusal(sweep(R"("points": [{"holes": 3}, {"nois.snr_db": 3}])")), "nois"));
    CHECK(has(
        refusal(sweep(R"("grid": {"noise.snr": [3]})", R"("base": {"evaluations_per_chain": 5})")),
        "noise.snr: unknown key"));
    // Empty grid, an empty list of values, an empty list of points, neither, both.
    CHECK(has(refusal(sweep(R"("grid": {})")), "grid: empty grid"));
    CHECK(has(refusal(sweep(R"("grid": {"holes": []})")), "grid.holes: must be a non-empty"));
    CHECK(has(refusal(sweep(R"("grid": {"holes": 3})")), "grid.holes: must be a non-empty"));
    CHECK(has(refusal(sweep(R"("points": [])")), "points: empty list"));
    CHECK(has(refusal(sweep(R"("base2": 1)")), "base2"));
    CHECK(has(refusal(R"({"format": "pinmask-sweep", "version": 1})"), "grid: missing"));
    CHECK(has(refusal(sweep(R"("grid": {"holes": [3]}, "points": [{}])")), "not both"));
    // Incompatible values: a Gaussian SNR under the photon model, a sensor key under the
    // Gaussian model, a time budget, a camera field without a base camera, no evaluation budget.
    CHECK(has(refusal(sweep(R"("grid": {"noise.snr_db": [10, 20]})")),
              "noise.snr_db: belongs to the gaussian model"));
    CHECK(has(refusal(sweep(R"("grid": {"noise.read_noise_e": [1, 2]})",
                            R"("base": {"evaluations_per_chain": 5})")),
              "noise.read_noise_e: belongs to the photon model"));
    CHECK(has(refusal(sweep(R"("grid": {"time": ["1s", "2s"]})")), "grid.time"));
    CHECK(has(refusal(sweep(R"("grid": {"optics.pinhole_m": [3e-4, 4e-4]})")),
              "grid.optics.pinhole_m: varies a camera field"));
    CHECK(has(refusal(sweep(R"("grid": {"holes": [3]})", R"("base": {"grid": 8})")),
              "evaluations_per_chain: a sweep needs an evaluation budget"));
    CHECK(has(refusal(sweep(R"("grid": {"evaluations_per_chain": [10, 0]})")),
              "evaluations_per_chain"));
    CHECK(has(refusal(sweep(R"("grid": {"format": ["x"]})")), "grid.format: 'format' cannot vary"));
    CHECK(
        has(refusal(sweep(R"("grid": {"threads": [1, 0]})")), "threads: must be >= 1 in a sweep"));
    // A value the search codec refuses, named with the point.
    const std::string bad_holes = refusal(sweep(R"("grid": {"holes": [3, 0]})"));
    CHECK(has(bad_holes, "grid point 1 (holes = 0): holes: 0 must be >= 1"));
    CHECK(has(refusal(sweep(R"("grid": {"holes": [3], "seed": [-1]})")), "seed"));
    // A grid of more points than kMaxSweepPoints (each point is a whole search).
    std::string many = "[";
    for (int i = 0; i < 200; ++i) many += (i ? "," : "") + std::to_string(i + 1);
    many += "]";
    CHECK(has(refusal(sweep(R"("grid": {"holes": )" + many + R"(, "seed": )" + many + "}")),
              "more than 10000 points"));
    CHECK(has(refusal("{"), "invalid JSON"));
    CHECK(has(refusal(R"({"format": "pinmask-search-config", "version": 1})"), "not a sweep file"));
}
