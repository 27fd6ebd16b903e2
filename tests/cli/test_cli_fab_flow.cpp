// Design to photomask with cameras that are not the paper's: `design --solve` puts the pinhole on
// the fabrication grid, `generate`, `export --vendor V` and `check` (no flags: the rules come from
// the export sidecar) agree that the mask is clean, and a mask one grid step too close fails all
// three with the same pair distance and limit. The expected pitches are computed here from the
// camera relations (d = N w / |1 - f/f' + f/u|, rounded to the grid by hand).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_run.hpp"

using pinmask::test::CliResult;
using pinmask::test::run_cli;
using pinmask::test::TempDir;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// The NIR camera of the issue: 5.86 um pixels, 1920 x 1200, f' = 75 mm, f = 45 mm, u = 1.2 m.
const std::string kNir =
    "--pixel-pitch 5.86um --sensor 1920x1200 --lens-focal 75mm --sensor-distance 45mm "
    "--object-distance 1.2m --wavelength 850nm";
// A machine-vision camera at 1.5 m, made on a film plotter's 1 um grid.
const std::string kFine =
    "--pixel-pitch 3.45um --sensor 2448x2048 --lens-focal 25mm --sensor-distance 20mm "
    "--object-distance 1.5m --wavelength 530nm";

double magnification(double f, double f_lens, double u) { return 1.0 - f / f_lens + f / u; }

// d for N whole pixels per cell at u, in nm, and the same on a grid of g nm (nearest multiple).
double solved_nm(int n_px, double w, double m) { return n_px * w / m * 1e9; }
long long on_grid(double nm, long long g) { return std::llround(nm / double(g)) * g; }

CliResult ok(const std::string& args) {
    const CliResult r = run_cli(args);
    INFO(args << "\nstdout: " << r.out << "\nstderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return r;
}

std::string um3(double nm) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.3f um", nm * 1e-3);
    return buf;
}

struct Flow {
    std::string camera, vendor, export_flags, file;
    int n_px;
    double w, m;
    long long grid_nm;
};

// design --solve -> generate -> export --vendor -> check (no flags): clean everywhere.
void clean_flow(const Flow& f, const TempDir& dir) {
    const std::string cam = dir / "cam.camera.json", mask = dir / "m.mask.json";
    const auto design = nlohmann::json::parse(ok("design " + f.camera + " --pixels-per-cell " +
                                                 std::to_string(f.n_px) + " --vendor " + f.vendor +
                                                 " --save-camera " + cam + " --json")
                                                  .out);
    const double exact = solved_nm(f.n_px, f.w, f.m);
    const long long grid_pitch = on_grid(exact, f.grid_nm);
    CHECK(std::fabs(exact - double(grid_pitch)) > 1e-3);  // the solution is off the grid
    CHECK(design["pinhole_solved_m"].get<double>() * 1e9 == doctest::Approx(exact).epsilon(1e-12));
    CHECK(std::llround(design["camera"]["pinhole_m"].get<double>() * 1e9) == grid_pitch);
    CHECK(std::fabs(design["camera"]["pinhole_m"].get<double>() * 1e9 - double(grid_pitch)) < 1e-6);
    // The table's shift of the pitch at u is the grid's: (P - d) |M(u)| / w.
    const double shift = (double(grid_pitch) - exact) * 1e-9 * f.m / f.w;
    CHECK(design["grid_pitch_shift_px"].get<double>() == doctest::Approx(shift).epsilon(1e-6));
    CHECK(design["integer_pixels_per_cell"] == f.n_px);
    CHECK(design["psf_size_px"] == 16 * f.n_px);

    const auto gen =
        nlohmann::json::parse(ok("generate --camera " + cam + " --seed 5 --json -o " + mask).out);
    CHECK(gen["spacing_violations"] == 0);
    CHECK(std::llround(gen["spacing_limit_m"].get<double>() * 1e9) == 2 * grid_pitch);

    const std::string fab = (dir.path / "fab").string();
    const CliResult ex =
        ok("export " + mask + " --vendor " + f.vendor + " " + f.export_flags + " -o " + fab);
    CHECK(contains(ex.out, "): clean"));
    CHECK(contains(ex.out, um3(2.0 * double(grid_pitch))));
    const CliResult ck = ok("check " + fab + "/m." + f.file + " --json");
    const auto j = nlohmann::json::parse(ck.out);
    CHECK(j["clean"] == true);
    CHECK(j["rules_from"] == "the export sidecar");
    CHECK(j["rules"]["min_center_spacing_um"].get<double>() ==
          doctest::Approx(2e-3 * double(grid_pitch)).epsilon(1e-12));
    CHECK(j["measured"]["min_center_spacing_um"].get<double>() >=
          j["rules"]["min_center_spacing_um"].get<double>() - 1e-6);
}

// A MURA keeps pinholes one cell apart; a rule of one cell plus one grid step makes every such
// pair one grid step too close. generate refuses it, export and check report it, all with the
// same distance and limit.
void one_step_too_close(const Flow& f, const TempDir& dir) {
    const std::string cam = dir / "cam.camera.json", mask = dir / "mura.mask.json";
    const double exact = solved_nm(f.n_px, f.w, f.m);
    const long long p = on_grid(exact, f.grid_nm);
    char spacing[64];
    std::snprintf(spacing, sizeof spacing, "%.17g", double(p + f.grid_nm) / double(p));
    const std::string pair = "centres " + um3(double(p)) + " apart < " + um3(double(p + f.grid_nm));
    const std::string gen =
        "generate --camera " + cam + " --family mura --grid 5 --spacing " + spacing + " -o " + mask;
    const CliResult refused = run_cli(gen);
    INFO(refused.err);
    CHECK(refused.exit_code == 2);
    CHECK(contains(refused.err, pair));
    ok(gen + " --allow-violations");
    const std::string fab = (dir.path / "fab-mura").string();
    const CliResult ex = run_cli("export " + mask + " --vendor " + f.vendor + " " + f.export_flags +
                                 " --hole-side " + std::to_string(p / 2) +
                                 "nm --allow-spacing-violations --write-on-violations -o " + fab);
    INFO(ex.out << ex.err);
    CHECK(ex.exit_code == 1);
    CHECK(contains(ex.out, "VIOLATIONS"));
    CHECK(contains(ex.out, pair));
    CHECK(contains(ex.err, "pinhole centres >= " + um3(double(p + f.grid_nm))));
    const CliResult ck = run_cli("check " + fab + "/mura." + f.file);
    INFO(ck.out << ck.err);
    CHECK(ck.exit_code == 1);
    CHECK(contains(ck.out, pair));
    CHECK(contains(ck.out, "FAILED"));
}

}  // namespace

TEST_CASE("NIR camera on a chrome photomask: solved pinhole off the 1 nm grid, clean end to end") {
    TempDir dir("fab-nir");
    const Flow f{kNir,
                 "chrome-photomask",
                 "--min-feature 2um",
                 "gds",
                 34,
                 5.86e-6,
                 magnification(0.045, 0.075, 1.2),
                 1};
    clean_flow(f, dir);
    // The shop's 2 um rule travels in the sidecar.
    const auto j = nlohmann::json::parse(ok("check " + dir / "fab/m.gds" + " --json").out);
    CHECK(j["vendor"] == "chrome");
    CHECK(j["rules"]["min_feature_um"].get<double>() == doctest::Approx(2.0));
    one_step_too_close(f, dir);
}

TEST_CASE("3.45 um camera on a film plotter: pinhole solved onto the 1 um grid, clean end to end") {
    TempDir dir("fab-fine");
    const Flow f{
        kFine, "film-plotter", "--format dxf", "dxf", 21, 3.45e-6, magnification(0.020, 0.025, 1.5),
        1000};
    clean_flow(f, dir);
    one_step_too_close(f, dir);
}

TEST_CASE("a pinhole off the grid is drawn at the grid pitch: export and check agree") {
    // The d = 455.40571 um given as is: export draws 455.406 um cells and says so.
    TempDir dir("fab-offgrid");
    const std::string mask = dir / "m.mask.json";
    ok("generate " + kNir +
       " --pinhole 455.40571um --pixels-per-cell 34 --family paper --seed 2 "
       "-o " +
       mask);
    const CliResult ex =
        ok("export " + mask + " --vendor chrome-photomask -o " + (dir.path / "fab").string());
    CHECK(contains(ex.out, "not on the 1 nm grid"));
    CHECK(contains(ex.out, "455406 nm"));
    CHECK(contains(ex.out, "): clean"));
    ok("check " + dir / "fab/m.oas");
}

TEST_CASE("export --vendor list needs no mask; check --vendor and --min-space override") {
    const CliResult list = ok("export --vendor list");
    CHECK(contains(list.out, "chrome-photomask"));
    CHECK(run_cli("export").exit_code == 2);
    TempDir dir("fab-override");
    const std::string mask = dir / "m.mask.json";
    ok("generate --seed 3 -o " + mask);
    ok("export " + mask + " --vendor chrome-photomask -o " + (dir.path / "fab").string());
    const std::string gds = dir / "fab/m.gds";
    // Sidecar rules (chrome, 1 um) pass; the film plotter's 16 um rules pass too (440 um cells);
    // a 500 um space cannot (neighbouring pinholes are 440 um apart edge to edge at most 2 cells).
    CHECK(nlohmann::json::parse(ok("check " + gds + " --json").out)["vendor"] == "chrome");
    const auto film = nlohmann::json::parse(ok("check " + gds + " --vendor film --json").out);
    CHECK(film["rules_from"] == "given");
    CHECK(film["rules"]["min_gap_um"].get<double>() == doctest::Approx(16.0));
    const CliResult wide = run_cli("check " + gds + " --min-space 500um --json");
    CHECK(wide.exit_code == 1);
    CHECK(nlohmann::json::parse(wide.out)["rules"]["min_gap_um"].get<double>() ==
          doctest::Approx(500.0));
}

TEST_CASE("design of the NIR camera is at u throughout: 544 px PSF, 34 px per cell, mismatch 0") {
    const auto j = nlohmann::json::parse(ok("design " + kNir + " --pixels-per-cell 34 --json").out);
    const double m = magnification(0.045, 0.075, 1.2), w = 5.86e-6;
    const double d = 455406e-9;  // the solved 455.405714 um on the 1 nm grid
    CHECK(j["camera"]["pinhole_m"].get<double>() == doctest::Approx(d).epsilon(1e-12));
    CHECK(j["psf_size_px"] == 544);
    CHECK(j["integer_pixels_per_cell"] == 34);
    CHECK(j["whole_pixels_per_cell_at_u"] == 34);
    // 16 |d M(u) / w - 34|: the grid's 1e-4 px share, against the N-pixel model at u.
    const double mismatch = 16 * std::fabs(d * m / w - 34);
    CHECK(mismatch < 1e-3);
    CHECK(j["lsi_mismatch_px"].get<double>() == doctest::Approx(mismatch).epsilon(1e-6));
    CHECK(j["lsi_shift_invariant"] == true);
    CHECK(j["periods_on_sensor"]["cols"].get<double>() == doctest::Approx(1920.0 / 544));
    // The distant-object figures stay, labelled: 31 px per cell, 496 px, f s_max / (u w).
    CHECK(j["integer_pixels_per_cell_at_inf"] == 31);
    CHECK(j["psf_size_at_inf_px"] == 496);
    CHECK(j["lsi_mismatch_at_inf_px"].get<double>() ==
          doctest::Approx(0.045 * 16 * d / (1.2 * w)).epsilon(1e-9));
    const CliResult table = ok("design " + kNir + " --pixels-per-cell 34");
    CHECK(contains(table.out, "544 x 544 px"));
    CHECK(contains(table.out, "496 x 496 px"));
    CHECK(contains(table.out, "u = inf"));
    CHECK(contains(table.out, "pitch at u moved by the grid"));
    CHECK_FALSE(contains(table.out, "NOT shift invariant"));
}
