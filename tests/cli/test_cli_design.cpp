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

// `pinmask design ARGS` is refused: exit 2, `says` on stderr, nothing on stdout.
void refused(const std::string& args, const std::string& says) {
    const auto r = run_cli("design " + args);
    INFO(args << " -> " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, says));
    CHECK(r.out.empty());
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
    CHECK(std::fabs(j["fresnel_number_with_lens_at_inf"].get<double>() - 0.87) <=
          kHalfUnit2ndDecimal);
    CHECK(std::fabs(j["effective_distance_at_inf_m"].get<double>() - 101.5e-3) <=
          kHalfUnit1stDecimalMm);
    CHECK(std::fabs(j["geometric_spot_at_inf_m"].get<double>() - 0.238e-3) <=
          kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(j["geometric_spot_at_u_m"].get<double>() - 0.242e-3) <= kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(j["pixels_per_cell_at_inf"].get<double>() - 7.94) <= kHalfUnit2ndDecimal);
    CHECK(std::fabs(j["pixels_per_cell_at_u"].get<double>() - 8.08) <= kHalfUnit2ndDecimal);
    CHECK(j["integer_pixels_per_cell"] == 8);
    CHECK(std::fabs(j["pinhole_for_integer_pixels_at_inf_m"].get<double>() - 443e-6) <= 0.5e-6);
    CHECK(std::fabs(j["lsi_min_object_distance_at_inf_m"].get<double>() - 12.9) <=
          kHalfUnit1stDecimal);
    CHECK(std::fabs(j["lsi_mismatch_at_inf_px"].get<double>() - 2.0) <= 0.5);
    CHECK(j["psf_size_px"] == 128);
    CHECK(j["periods_on_sensor"]["cols"] == 5.625);
    // At u = 6 m: 8.08 px per cell, N = 8, so one period is 16 x 0.08 px off the 8-px model;
    // the plain keys are at u, the "_at_inf" ones the paper's distant-object values.
    CHECK(std::fabs(j["pixels_per_cell"].get<double>() - 8.08) <= kHalfUnit2ndDecimal);
    CHECK(j["lsi_mismatch_px"].get<double>() ==
          doctest::Approx(16 * (j["pixels_per_cell"].get<double>() - 8)).epsilon(1e-12));
    CHECK(j["psf_size_at_inf_px"] == 128);
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
    CHECK(j["lsi_mismatch_at_inf_px"] == 0.0);
    const auto past = design_json("--sensor-distance 200mm");
    CHECK(past["effective_distance_m"].get<double>() < 0);
    const auto no_lens = design_json("--lens-focal inf");
    CHECK(no_lens["magnification_at_inf"] == 1.0);
    CHECK(design_json("--kernel box")["kernel_model"] == "box");
}

TEST_CASE("invalid input exits 2 naming the flag") {
    refused("--sensor-distance 0", "--sensor-distance");
    refused("--wavelength 0", "--wavelength");
    refused("--lens-focal -1", "--lens-focal");
    refused("--pinhole 3furlongs", "--pinhole");
    refused("--pixel-pitch=-30um", "--pixel-pitch");
}

TEST_CASE("more invalid input: units, models, geometry") {
    refused("--wavelength 550xm", "--wavelength");
    refused("--kernel gauss", "--kernel");
    refused("--grid 0", "--grid");
    refused("--holes 300", "--holes");
    refused("--tiles 0", "--tiles");
    refused("--lsi-tolerance 0", "--lsi-tolerance");
    CHECK(run_cli("design --help").exit_code == 0);
    CHECK(contains(run_cli("design --help").out, "Example"));
}

namespace {

// A machine-vision camera: 3.45 um pixels, 25 mm lens, sensor 20 mm behind, object at 2 m.
const std::string kFinePixelCamera =
    "--pixel-pitch 3.45um --sensor 2448x2048 --lens-focal 25mm --sensor-distance 20mm "
    "--object-distance 2m --wavelength 530nm";

// d = 345.0 um is the reference value to four digits: +-0.1 %.
constexpr double kQuotedRel = 1e-3;
// JSON round trip of doubles (17 significant digits) and two evaluations of one closed form.
constexpr double kRoundTripRel = 1e-9;

}  // namespace

TEST_CASE("design --pixels-per-cell 21 for the 3.45 um camera: d = 345.0 um, range by the rule") {
    const auto j = design_json(kFinePixelCamera + " --pixels-per-cell 21");
    const double d = j["pinhole_for_pixels_per_cell_m"].get<double>();
    CHECK(std::fabs(d / 345.0e-6 - 1.0) <= kQuotedRel);
    CHECK(std::fabs(j["camera"]["pinhole_m"].get<double>() - d) <= kRoundTripRel * d);
    CHECK(j["whole_pixels_per_cell_at_u"] == 21);
    CHECK(std::fabs(j["pixels_per_cell_at_u"].get<double>() - 21.0) <= 1e-9);
    CHECK(std::fabs(j["lsi_mismatch_at_u_px"].get<double>()) <= 1e-9);
    // Direct evaluation of the tolerance: f s_max |1/u' - 1/u| / w = 1 px at both ends.
    const auto range = j["object_distance_range_m"];
    REQUIRE(range.size() == 2);
    REQUIRE(range[1].is_number());
    const double s_max = 16 * d, f = 0.020, w = 3.45e-6, u = 2.0;
    for (int end = 0; end < 2; ++end) {
        const double u_end = range[end].get<double>();
        CHECK(std::fabs(f * s_max * std::fabs(1.0 / u_end - 1.0 / u) / w - 1.0) <= kRoundTripRel);
    }
    CHECK(range[0].get<double>() < u);
    CHECK(range[1].get<double>() > u);
    CHECK(std::fabs(j["optimum_pinhole_lensless_m"].get<double>() - 160.6e-6) <= 0.05e-6);
    CHECK(j["optimum_pinhole_with_lens_m"].get<double>() > 340e-6);
    CHECK(j.contains("optimum_pinhole_m"));  // the existing key stays
    // --solve pinhole from a pinhole near 21 px gives the same design.
    const auto solved = design_json(kFinePixelCamera + " --pinhole 340um --solve pinhole");
    CHECK(solved["whole_pixels_per_cell_at_u"] == 21);
    CHECK(std::fabs(solved["camera"]["pinhole_m"].get<double>() - d) <= kRoundTripRel * d);
    // A large tolerance reaches infinity: null with a note.
    const auto loose = design_json(kFinePixelCamera + " --pixels-per-cell 21 --lsi-tolerance 100");
    CHECK(loose["object_distance_range_m"][1].is_null());
    CHECK(loose["notes"].contains("object_distance_range_m"));
}

TEST_CASE("design table: both optima with formulas, the regime line and the spread warning") {
    const auto r = run_cli("design " + kFinePixelCamera + " --pinhole 160.6um");
    REQUIRE(r.exit_code == 0);
    CHECK(contains(r.out, "1.56 sqrt(lambda f)"));
    CHECK(contains(r.out, "1.56 sqrt(lambda |z_eff(u)|)"));
    CHECK(contains(r.out, "regime"));
    CHECK(contains(r.out, "WARNING: spots spread over more than one cell"));
    CHECK(contains(r.out, "usable object distances"));
    const auto ok = run_cli("design " + kFinePixelCamera + " --pixels-per-cell 21");
    CHECK_FALSE(contains(ok.out, "WARNING"));
}

TEST_CASE("design working-distance edge cases exit 2 with a message") {
    refused("--object-distance 100mm", "inside the focal length");
    refused("--lens-focal 55mm --object-distance inf --pixels-per-cell 8", "z_eff is infinite");
    refused("--lsi-tolerance 0", "empty object-distance range");
    refused("--pixels-per-cell 21 --pinhole 300um", "--pixels-per-cell");
    refused("--pixels-per-cell 0", "--pixels-per-cell");
    refused("--solve focus", "--solve");
    // f = f' at a finite u is legal: M = f/u = 0.00917, so 2 px per cell needs d = 6.5 mm; 8 px
    // would need 26 mm, larger than any pinhole: refused naming the flag that asked for it.
    CHECK(run_cli("design --lens-focal 55mm --object-distance 6m --pixels-per-cell 2").exit_code ==
          0);
    refused("--lens-focal 55mm --object-distance 6m --pixels-per-cell 8",
            "--pixels-per-cell = 8: needs d = 26.18 mm for 8 whole pixels per cell at u, larger "
            "than any pinhole");
}

TEST_CASE("design --save-camera writes a camera file; --camera reads it; flags override it") {
    pinmask::test::TempDir dir("camera-file");
    const std::string file = dir / "my.camera.json";
    const auto saved =
        run_cli("design " + kFinePixelCamera + " --pixels-per-cell 21 --save-camera " + file);
    INFO(saved.err);
    REQUIRE(saved.exit_code == 0);
    CHECK(contains(saved.out, "solved for N px per cell at u"));
    CHECK(contains(saved.out, "flag"));
    // Read back: the solved pinhole, the file as the source, a flag overriding u.
    const auto j = design_json("--camera " + file + " --object-distance 3m");
    CHECK(std::fabs(j["camera"]["pinhole_m"].get<double>() / 345.0e-6 - 1.0) <= kQuotedRel);
    CHECK(j["camera"]["object_distance_m"] == 3.0);
    CHECK(j["input_sources"]["d (pinhole)"] == "camera file");
    CHECK(j["input_sources"]["u (object distance)"] == "flag");
    // Without flags or file, the inputs are marked as the paper preset's defaults.
    const auto preset = run_cli("design");
    CHECK(contains(preset.out, "paper preset default"));
    // Other commands take the file too.
    const auto gen = run_cli("generate --camera " + file + " --seed 1 -o " + (dir / "m.mask.json"));
    CHECK(gen.exit_code == 0);
    // Bad input: missing file, a folder that does not exist, overwriting the input.
    refused("--camera " + (dir / "nope.camera.json"), "nope.camera.json");
    refused("--save-camera " + (dir / "no/such.camera.json"), "--save-camera");
    refused("--camera " + file + " --save-camera " + file, "overwrite");
}

TEST_CASE(
    "--bandwidth: design shows the band and psf's kernel warnings; masks and cameras carry it") {
    pinmask::test::TempDir dir("bandwidth");
    // An NIR camera lit by an 850 nm LED with a 30 nm band; d for 34 px per cell at u = 1.2 m.
    const std::string nir =
        "--pixel-pitch 5.86um --sensor 1920x1200 --lens-focal 75mm --sensor-distance 45mm "
        "--object-distance 1.2m --wavelength 850nm --pinhole 455.406um --bandwidth 30nm";
    const auto j = design_json(nir);
    CHECK(j["camera"]["bandwidth_m"].get<double>() == doctest::Approx(30e-9).epsilon(1e-15));
    CHECK(j["spectrum"]["bandwidth_m"] == j["camera"]["bandwidth_m"]);
    REQUIRE(j["spectrum"]["wavelengths"].size() == 13);
    CHECK(j["spectrum"]["wavelengths"][0][0].get<double>() == doctest::Approx(805e-9));
    CHECK(j["spectrum"]["wavelengths"][12][0].get<double>() == doctest::Approx(895e-9));
    CHECK(j["input_sources"]["B (bandwidth, FWHM)"] == "flag");
    CHECK(j["whole_pixels_per_cell_at_u"] == 34);
    const auto table = run_cli("design " + nir);
    CHECK(contains(table.out, "850 nm, FWHM 30 nm: 13 samples 805 nm .. 895 nm"));
    CHECK(contains(table.out, "kernel support"));

    // The mask generated with the band carries it, and psf warns exactly as design did.
    const std::string mask = dir / "nir.mask.json";
    const auto gen = run_cli("generate " + nir + " --seed 3 -o " + mask);
    INFO(gen.err);
    REQUIRE(gen.exit_code == 0);
    const auto m = nlohmann::json::parse(pinmask::test::slurp(mask));
    CHECK(m["optics"]["bandwidth_m"] == j["camera"]["bandwidth_m"]);
    const auto psf = run_cli("psf " + mask + " --json -o " + (dir / "p.tiff"));
    INFO(psf.err);
    REQUIRE(psf.exit_code == 0);
    const auto p = nlohmann::json::parse(psf.out);
    CHECK(p["kernel"]["wavelengths"].size() == 13);
    CHECK(p["kernel"]["enclosed_energy"] == j["kernel"]["enclosed_energy"]);
    // psf's warnings word for word, except that design names where --energy lives.
    auto design_words = p["warnings"];
    for (auto& w : design_words) {
        std::string text = w.get<std::string>();
        const auto at = text.find("raise --energy");
        if (at != std::string::npos)
            text.insert(at + 14, " (a flag of pinmask psf, not of design)");
        w = text;
    }
    CHECK(design_words == j["kernel_warnings"]);

    // The camera file keeps the band; --camera gives it to every command.
    const std::string cam = dir / "nir.camera.json";
    REQUIRE(run_cli("design " + nir + " --save-camera " + cam).exit_code == 0);
    const auto again = design_json("--camera " + cam);
    CHECK(again["camera"]["bandwidth_m"] == j["camera"]["bandwidth_m"]);
    CHECK(again["input_sources"]["B (bandwidth, FWHM)"] == "camera file");
    CHECK(again["kernel_warnings"] == j["kernel_warnings"]);

    // Without the flag: one wavelength, and no bandwidth key in the files written.
    const auto mono = design_json("--preset paper");
    CHECK(mono["spectrum"]["wavelengths"].size() == 1);
    REQUIRE(run_cli("generate --seed 3 -o " + (dir / "mono.mask.json")).exit_code == 0);
    CHECK(!contains(pinmask::test::slurp(dir / "mono.mask.json"), "bandwidth"));

    for (const char* bad : {"-5nm", "nan", "1um", "300nm"}) {
        const auto r = run_cli(std::string("design --bandwidth ") + bad);
        INFO(bad << " -> " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, "--bandwidth"));
    }
}
