// `pinmask design` end to end: the paper's figures in --json, the table, limits and bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

nlohmann::json design_json(const std::string& args) {
    const auto r = run_cli("design --json " + args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
}

// Half a unit in the last published digit (the same bounds as tests/design/test_optics.cpp).
constexpr double kHalfUnit3rdDecimalMm = 0.0005e-3;
constexpr double kHalfUnit1stDecimalMm = 0.05e-3;
constexpr double kHalfUnit1stDecimal = 0.05;
constexpr double kHalfUnit2ndDecimal = 0.005;

}  // namespace

TEST_CASE("design --json gives the paper's numbers with unit-carrying keys") {
    const auto j = design_json("--preset paper");
    CHECK(std::fabs(j["optimum_pinhole_m"].get<double>() - 0.271e-3) <= kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(j["fresnel_number"].get<double>() - 1.6) <= kHalfUnit1stDecimal);
    CHECK(std::fabs(j["fresnel_number_with_lens"].get<double>() - 0.87) <= kHalfUnit2ndDecimal);
    CHECK(std::fabs(j["effective_distance_m"].get<double>() - 101.5e-3) <= kHalfUnit1stDecimalMm);
    CHECK(std::fabs(j["geometric_spot_m"].get<double>() - 0.238e-3) <= kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(j["geometric_spot_at_u_m"].get<double>() - 0.242e-3) <= kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(j["pixels_per_cell"].get<double>() - 7.94) <= kHalfUnit2ndDecimal);
    CHECK(std::fabs(j["pixels_per_cell_at_u"].get<double>() - 8.08) <= kHalfUnit2ndDecimal);
    CHECK(j["integer_pixels_per_cell"] == 8);
    CHECK(std::fabs(j["pinhole_for_integer_pixels_m"].get<double>() - 443e-6) <= 0.5e-6);
    CHECK(std::fabs(j["lsi_min_object_distance_m"].get<double>() - 12.9) <= kHalfUnit1stDecimal);
    CHECK(std::fabs(j["lsi_mismatch_px"].get<double>() - 2.0) <= 0.5);
    CHECK(j["psf_size_px"] == 128);
    CHECK(j["periods_on_sensor"]["cols"] == 5.625);
    CHECK(j["open_fraction"] == 0.078125);
    CHECK(j["light_gain"] == 20.0);
    CHECK(j["kernel_model"] == "fresnel");
    CHECK(j["notes"].empty());
}

TEST_CASE("design table: quantity, value with unit, note") {
    const auto r = run_cli("design");
    REQUIRE(r.exit_code == 0);
    CHECK(contains(r.out, "quantity"));
    CHECK(contains(r.out, "238.3 um"));
    CHECK(contains(r.out, "101.5 mm"));
    CHECK(contains(r.out, "NOT shift invariant"));
    CHECK(contains(r.out, "fresnel"));
}

TEST_CASE("f = f' and u = inf are valid; infinities are null with a note") {
    const auto j = design_json("--lens-focal 55mm --object-distance inf");
    CHECK(j["effective_distance_m"].is_null());
    CHECK(j["pinhole_for_integer_pixels_m"].is_null());
    CHECK(contains(j["notes"]["effective_distance_m"].get<std::string>(), "f = f'"));
    CHECK(j["fresnel_number_with_lens"] == 0.0);
    CHECK(j["kernel_model"] == "fraunhofer");
    CHECK(j["lsi_mismatch_px"] == 0.0);
    CHECK(j["lsi_shift_invariant"] == true);
    const auto past = design_json("--sensor-distance 200mm");
    CHECK(past["effective_distance_m"].get<double>() < 0);
    const auto no_lens = design_json("--lens-focal inf");
    CHECK(no_lens["magnification"] == 1.0);
    CHECK(design_json("--kernel box")["kernel_model"] == "box");
}

TEST_CASE("invalid input exits 2 naming the flag") {
    auto refused = [](const std::string& args, const std::string& flag) {
        const auto r = run_cli("design " + args);
        INFO(args << " -> " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, flag));
        CHECK(r.out.empty());
    };
    refused("--sensor-distance 0", "--sensor-distance");
    refused("--wavelength 0", "--wavelength");
    refused("--lens-focal -1", "--lens-focal");
    refused("--pinhole 3furlongs", "--pinhole");
    refused("--pixel-pitch=-30um", "--pixel-pitch");
}

TEST_CASE("more invalid input: units, models, geometry") {
    auto refused = [](const std::string& args, const std::string& flag) {
        const auto r = run_cli("design " + args);
        INFO(args << " -> " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, flag));
    };
    refused("--wavelength 550xm", "--wavelength");
    refused("--kernel gauss", "--kernel");
    refused("--grid 0", "--grid");
    refused("--holes 300", "--holes");
    refused("--tiles 0", "--tiles");
    refused("--lsi-tolerance 0", "--lsi-tolerance");
    CHECK(run_cli("design --help").exit_code == 0);
    CHECK(contains(run_cli("design --help").out, "Example"));
}
