// `pinmask design` where the user leaves something out or types a number without its unit: a
// camera of other optics without --pinhole gets the whole-pixel pinhole nearest its optimum and
// says so; a solve far from the optimum says where it is; a kernel warning names only flags
// design has; the table and --json carry the image distance and the diffraction first zero.
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

// The machine-vision camera of test_cli_design.cpp, without its pinhole.
const std::string kVision =
    "--pixel-pitch 3.45um --sensor 2448x2048 --lens-focal 25mm --sensor-distance 20mm "
    "--object-distance 2m --wavelength 530nm";

}  // namespace

TEST_CASE("design without --pinhole on other optics: the whole-pixel optimum, said on stderr") {
    const auto r = run_cli("design --json " + kVision);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    // Written out: 1/z = 1/f - 1/f' + 1/u, d_opt = 1.56 sqrt(lambda z), M = 1 - f/f' + f/u,
    // N = round(d_opt M / w), d = N w / M.
    const double f = 20e-3, fl = 25e-3, u = 2.0, lambda = 530e-9, w = 3.45e-6;
    const double z = 1.0 / (1.0 / f - 1.0 / fl + 1.0 / u), m = 1.0 - f / fl + f / u;
    const double opt = 1.56 * std::sqrt(lambda * z);
    const double n = std::round(opt * m / w);
    const double d = j["camera"]["pinhole_m"].get<double>();
    CHECK(std::fabs(d - n * w / m) <= 0.5e-9 + 1e-15);
    CHECK(j["whole_pixels_per_cell_at_u"] == static_cast<long long>(n));
    CHECK(j["lsi_shift_invariant"] == true);
    CHECK(j["input_sources"]["d (pinhole)"] == "whole-pixel optimum (no --pinhole given)");
    CHECK(contains(r.err, "pinmask: note: no --pinhole given: using d = "));
    CHECK(contains(r.err, "give --pinhole to choose another"));
    // Given --pinhole, or naming the preset, the pinhole is the user's and nothing is said.
    const auto given = run_cli("design --json " + kVision + " --pinhole 345um");
    REQUIRE(given.exit_code == 0);
    CHECK(nlohmann::json::parse(given.out)["camera"]["pinhole_m"].get<double>() ==
          doctest::Approx(345e-6).epsilon(1e-12));
    CHECK_FALSE(contains(given.err, "no --pinhole given"));
    const auto paper = run_cli("design --json --preset paper --wavelength 633nm");
    REQUIRE(paper.exit_code == 0);
    CHECK(nlohmann::json::parse(paper.out)["camera"]["pinhole_m"].get<double>() == 440e-6);
    CHECK_FALSE(contains(paper.err, "no --pinhole given"));
    // --pixels-per-cell solves the pinhole itself: no default is chosen or said first.
    const auto solved = run_cli("design --json " + kVision + " --pixels-per-cell 21");
    REQUIRE(solved.exit_code == 0);
    CHECK_FALSE(contains(solved.err, "no --pinhole given"));
}

TEST_CASE("design --solve pinhole from a start far from the optimum says where the optimum is") {
    // Lensless, 5 mm to the sensor, u = 6 m: z = 1/(1/5mm + 1/6m) = 4.9958 mm, the optimum
    // 1.56 sqrt(550 nm z) = 81.77 um; the start 440 um is 5.38x that.
    const auto r = run_cli(
        "design --json --preset paper --lens-focal inf --sensor-distance 5mm --solve pinhole");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(contains(
        r.err,
        "pinmask: warning: the solve starts from d = 440 um, 5.38x the diffraction optimum"));
    CHECK(contains(r.err, "give --pinhole near 81.77 um"));
    // A start near the optimum: no warning.
    const auto near = run_cli(
        "design --json --preset paper --lens-focal inf --sensor-distance 5mm --pinhole 90um "
        "--solve pinhole");
    REQUIRE(near.exit_code == 0);
    CHECK_FALSE(contains(near.err, "diffraction optimum"));
}

TEST_CASE("design's kernel warning names only flags design has") {
    // f = f' with u = inf: the sinc^2 kernel spreads past any support, so psf's energy warning
    // fires; design has no --energy, so the warning says which commands do.
    const auto r = run_cli("design --json --preset paper --object-distance inf --lens-focal 55mm");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    bool energy = false;
    for (const auto& w : j["kernel_warnings"]) {
        const std::string text = w.get<std::string>();
        if (!contains(text, "--energy")) continue;
        energy = true;
        CHECK(contains(text, "--energy (a flag of pinmask "));
        CHECK(contains(text, "psf"));
        CHECK(contains(text, ", not of design)"));
    }
    CHECK(energy);
}

TEST_CASE("design prints the image distance and the diffraction spot's first zero") {
    const auto r = run_cli("design --json --preset paper");
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    // 1/v = 1/f' - 1/u at f' = 120 mm, u = 6 m; lambda f / (d w) = 550 nm 55 mm / (440 um 30 um).
    CHECK(j["image_distance_at_u_m"].get<double>() ==
          doctest::Approx(1.0 / (1.0 / 0.12 - 1.0 / 6.0)).epsilon(1e-12));
    CHECK(j["diffraction_first_zero_px"].get<double>() ==
          doctest::Approx(550e-9 * 55e-3 / (440e-6 * 30e-6)).epsilon(1e-12));
    const auto table = run_cli("design --preset paper");
    REQUIRE(table.exit_code == 0);
    CHECK(contains(table.out, "image distance v at u"));
    CHECK(contains(table.out, "122.4 mm"));
    CHECK(contains(table.out, "diffraction first zero"));
    CHECK(contains(table.out, "2.29 px"));
    // No lens: no image, null with the reason.
    const auto lensless = run_cli("design --json --preset paper --lens-focal inf");
    REQUIRE(lensless.exit_code == 0);
    const auto l = nlohmann::json::parse(lensless.out);
    CHECK(l["image_distance_at_u_m"].is_null());
    CHECK(contains(l["notes"]["image_distance_at_u_m"].get<std::string>(), "no lens"));
}
