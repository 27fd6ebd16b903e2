// `pinmask check` end to end on masks built here with known answers: clean masks, spacing
// violations inside a tile and across a seam, gap limits at and beyond the rule, bad input, and
// fabrication files written by the export writers and read back.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "export/formats/gds_writer.hpp"
#include "export/layout/geometry.hpp"
#include "io/mask_json.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using pinmask::test::run_cli;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// JSON lengths are nm values times 1e-3 (one rounding) and areas nm^2 times 1e-6.
constexpr double kUnitConversion = 1e-12;

doctest::Approx um(double v) { return doctest::Approx(v).epsilon(kUnitConversion); }

// The paper camera (d = 440 um), an n x n pattern with the given pinholes and tiles.
Mask make_mask(int n, std::vector<Cell> holes, int tiles, bool violations_allowed = false) {
    Mask m;
    m.pattern.n = n;
    m.pattern.pinholes = std::move(holes);
    m.pattern.tiles_rows = m.pattern.tiles_cols = tiles;
    m.provenance.spacing_violations_allowed = violations_allowed;
    m.provenance.generator = "test_cli_check";
    return m;
}

std::string write_mask(const TempDir& dir, const std::string& name, const Mask& m) {
    const std::string path = dir / name;
    io::write_mask_file(path, m);
    return path;
}

nlohmann::json json_of(const test::CliResult& r) {
    INFO(r.err);
    return nlohmann::json::parse(r.out);
}

std::size_t count(const nlohmann::json& j, const std::string& rule) {
    return j["counts"].contains(rule) ? j["counts"][rule].get<std::size_t>() : 0;
}

}  // namespace

TEST_CASE("check: a mask meeting its spacing rule is clean (exit 0), in text and JSON") {
    TempDir dir("check-clean");
    const auto mask =
        write_mask(dir, "m.mask.json", make_mask(16, {{0, 0}, {0, 2}, {3, 5}, {8, 8}}, 2));
    const auto text = run_cli("check " + mask);
    INFO(text.err);
    CHECK(text.exit_code == 0);
    CHECK(text.out.find("result      clean") != std::string::npos);
    const auto r = run_cli("check --json " + mask);
    REQUIRE(r.exit_code == 0);
    const auto j = json_of(r);
    CHECK(j["clean"] == true);
    CHECK(j["kind"] == "mask");
    CHECK(j["polygons"] == 16);  // 4 pinholes x 2 x 2 tiles
    CHECK(j["rules"]["min_center_spacing_um"].get<double>() == um(880.0));
    CHECK(j["rules"]["min_gap_um"].get<double>() == um(16.0));
    CHECK(j["measured"]["min_center_spacing_um"].get<double>() == um(880.0));  // (0,0)-(0,2)
    CHECK(j["violations"].empty());
}

TEST_CASE("check: diagonal neighbours violate spacing and touch, in a tile and across a seam") {
    TempDir dir("check-viol");
    // (0,0) and (1,1) in each of the 4 tiles: 4 pairs sqrt(2) d apart, corners touching.
    const auto inside =
        write_mask(dir, "a.mask.json", make_mask(16, {{0, 0}, {1, 1}}, 2, /*allowed=*/true));
    auto r = run_cli("check --json " + inside);
    CHECK(r.exit_code == 1);
    auto j = json_of(r);
    CHECK(j["clean"] == false);
    CHECK(count(j, "spacing") == 4);
    CHECK(count(j, "touching") == 4);
    CHECK(j["measured"]["min_center_spacing_um"].get<double>() == um(440.0 * std::sqrt(2.0)));
    // (0,0) and (15,15) are torus neighbours: on the 2 x 2 tiled mask they meet once, where
    // tile (0,0)'s corner cell touches tile (1,1)'s.
    const auto seam =
        write_mask(dir, "b.mask.json", make_mask(16, {{0, 0}, {15, 15}}, 2, /*allowed=*/true));
    j = json_of(r = run_cli("check --json " + seam));
    CHECK(r.exit_code == 1);
    CHECK(count(j, "spacing") == 1);
    CHECK(count(j, "touching") == 1);
    const auto& v = j["violations"][0];
    CHECK(v["rule"] == "touching");
    CHECK(v["x_um"] == 0.0);  // the corner at the mask centre
    CHECK(v["y_um"] == 0.0);
    // Text output lists the violation with its location.
    r = run_cli("check " + seam);
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("(0.000, 0.000) um") != std::string::npos);
}

TEST_CASE("check: --min-gap exactly at the gap passes, a nanometre more fails") {
    TempDir dir("check-gap");
    // (0,0) and (0,2), one tile: the squares are 440 um apart edge to edge.
    const auto mask = write_mask(dir, "m.mask.json", make_mask(16, {{0, 0}, {0, 2}}, 1));
    CHECK(run_cli("check --min-gap 440um " + mask).exit_code == 0);
    const auto r = run_cli("check --json --min-gap 440.001um " + mask);
    CHECK(r.exit_code == 1);
    const auto j = json_of(r);
    CHECK(count(j, "gap") == 1);
    CHECK(j["violations"][0]["value"] == 440'000.0);
    CHECK(j["violations"][0]["unit"] == "nm");
    // A feature limit above the pinhole side flags both pinholes (width and height each).
    CHECK(count(json_of(run_cli("check --json --min-feature 0.5mm " + mask)), "feature") == 4);
}

TEST_CASE("check: bad input is exit 2 with a message naming the problem") {
    TempDir dir("check-bad");
    const auto mask = write_mask(dir, "m.mask.json", make_mask(16, {{0, 0}}, 1));
    auto r = run_cli("check --vendor glass " + mask);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("film, chrome, none") != std::string::npos);
    r = run_cli("check " + (dir / "missing.mask.json"));
    CHECK(r.exit_code == 2);
    CHECK(run_cli("check --min-gap 0um " + mask).exit_code == 2);
    CHECK(run_cli("check --mask " + mask + " " + mask).exit_code == 2);
    CHECK(run_cli("check " + (dir / "x.txt")).exit_code == 2);
    { std::ofstream(dir / "x.txt") << "not a layout\n"; }
    CHECK(run_cli("check " + (dir / "x.txt")).exit_code == 2);
}

TEST_CASE("check: a GDSII file read back matches its mask; another mask does not") {
    TempDir dir("check-gds");
    const Mask m = make_mask(16, {{0, 0}, {0, 2}, {3, 5}, {8, 8}}, 2);
    const auto mask = write_mask(dir, "m.mask.json", m);
    const std::string gds = dir / "m.gds";
    {
        std::ofstream out(gds, std::ios::binary);
        out << gds_stream(make_layout(m, LayoutOptions{}));
    }
    auto r = run_cli("check --json " + gds + " --mask " + mask);
    auto j = json_of(r);
    CHECK(r.exit_code == 0);
    CHECK(j["kind"] == "gds");
    CHECK(j["polygons"] == 16);
    CHECK(j["comparison"]["xor_area_um2"] == 0.0);
    CHECK(j["comparison"]["ok"] == true);
    // Without the mask the rings are checked on their own (no spacing rule): still clean.
    CHECK(run_cli("check " + gds).exit_code == 0);
    // A design with one pinhole moved: XOR = 2 pinholes' area per tile, hash differs.
    const auto other =
        write_mask(dir, "o.mask.json", make_mask(16, {{0, 0}, {0, 2}, {3, 5}, {8, 9}}, 2));
    j = json_of(r = run_cli("check --json " + gds + " --mask " + other));
    CHECK(r.exit_code == 1);
    CHECK(j["comparison"]["xor_area_um2"].get<double>() == um(4 * 2 * 440.0 * 440.0));
    CHECK(j["comparison"]["ok"] == false);
}

TEST_CASE("check: a dark-tone GDSII with frame and marks; the frame must be given to compare") {
    TempDir dir("check-dark");
    const Mask m = make_mask(16, {{0, 0}, {0, 2}, {3, 5}, {8, 8}}, 2);
    const auto mask = write_mask(dir, "m.mask.json", m);
    LayoutOptions o;
    o.tone = Tone::kDark;
    o.frame_m = 1e-3;
    o.marks = true;
    const std::string gds = dir / "d.gds";
    {
        std::ofstream out(gds, std::ios::binary);
        out << gds_stream(make_layout(m, o));
    }
    auto r = run_cli("check --json " + gds + " --mask " + mask + " --frame 1mm");
    auto j = json_of(r);
    CHECK(r.exit_code == 0);
    CHECK(j["tone"] == "dark");
    CHECK(j["annotations"] == 4);  // the crosses, outside the outline
    CHECK(j["comparison"]["xor_area_um2"] == 0.0);
    // The 16 pinholes are recovered as clear regions and meet the spacing rule exactly.
    CHECK(j["measured"]["min_center_spacing_um"].get<double>() == um(880.0));
    // Against a frameless design (the flag forgotten) the files differ: exit 1.
    j = json_of(r = run_cli("check --json " + gds + " --mask " + mask));
    CHECK(r.exit_code == 1);
    CHECK(j["comparison"]["ok"] == false);
    CHECK(j["comparison"]["xor_area_um2"].get<double>() > 0.0);
}

TEST_CASE("check FILE takes the export sidecar: clean on every format export writes, no flags") {
    TempDir dir("check-sidecar");
    // 16 x 16 pattern, 2 x 2 tiles, pinholes 2 cells apart.
    const std::string mask =
        write_mask(dir, "m.mask.json", make_mask(16, {{0, 0}, {3, 5}, {8, 2}, {12, 12}}, 2));
    struct Variant {
        std::string name, flags;
    };
    const std::vector<Variant> variants = {
        {"clear", "--marks --label --frame 1mm"},
        {"dark", "--tone positive --emulsion down --marks --label --frame 1mm --units mm"},
        {"round", "--shape circle --hole-side 300um --circles native --units in --label"},
        {"cells", "--hierarchy cells --grid 10nm --frame 500um --marks"},
        {"drawn", "--draw polygons --marks --label"},
    };
    for (const Variant& v : variants) {
        const std::string out = dir / v.name;
        // 10 um pixels for the pictures (the default 25400 dpi TIFF would be 20000^2 pixels).
        const auto e = run_cli("export '" + mask +
                               "' --format svg,gds,oasis,dxf,gerber,pdf,png,tiff1 --dpi 2540 "
                               "--no-psf " +
                               v.flags + " -o '" + out + "'");
        INFO(v.name << ": " << e.err);
        REQUIRE(e.exit_code == 0);
        for (const std::string ext : {"svg", "gds", "oas", "dxf", "gbr"}) {
            const auto c = run_cli("check '" + out + "/m." + ext + "' --json");
            INFO(v.name << " " << ext << ": " << c.err << c.out);
            CHECK(c.exit_code == 0);
            const auto j = json_of(c);
            CHECK(j["clean"] == true);
            CHECK(j["comparison"]["ok"] == true);
            CHECK(j["comparison"]["rings_only_in_file"] == 0);
            CHECK(j["settings"].get<std::string>().find("export.json") != std::string::npos);
        }
        // The pictures: compared with the design drawn the same way (no flags either).
        for (const std::string ext : {"pdf", "png", "tif"}) {
            const auto c = run_cli("check '" + out + "/m." + ext + "' --json");
            INFO(v.name << " " << ext << ": " << c.err << c.out);
            CHECK(c.exit_code == 0);
            const auto j = json_of(c);
            CHECK(j["clean"] == true);
            CHECK(j["picture"]["ok"] == true);
        }
    }
    // A picture of another design is not clean: the dark-tone TIFF checked against the clear
    // sidecar's settings (copied beside it) differs pixel by pixel.
    fs::copy_file(dir.path / "clear" / "m.export.json", dir.path / "dark" / "x.export.json");
    fs::copy_file(dir.path / "dark" / "m.tif", dir.path / "dark" / "x.tif");
    const auto other = run_cli("check '" + (dir / "dark") + "/x.tif' --json");
    CHECK(other.exit_code == 1);
    CHECK(json_of(other)["picture"]["ok"] == false);
    // A PNG without its sidecar has no known dpi: refused (exit 2) naming what is missing.
    const auto no_dpi =
        run_cli("check '" + (dir / "dark") + "/m.png' --no-sidecar --mask '" + mask + "'");
    CHECK(no_dpi.exit_code == 2);
    CHECK(no_dpi.err.find("png dpi") != std::string::npos);
    // An explicit flag that disagrees with the sidecar stops the check (exit 2, names the flag).
    const auto bad = run_cli("check '" + (dir / "dark") + "/m.gds' --frame 2mm");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--frame") != std::string::npos);
    const auto agree = run_cli("check '" + (dir / "dark") + "/m.gds' --frame 1mm --tone dark");
    CHECK(agree.exit_code == 0);
    // Without the sidecar and without the frame flag the dark-tone file does not match its
    // design: the sidecar is what makes the check right.
    const auto bare =
        run_cli("check '" + (dir / "dark") + "/m.gds' --no-sidecar --mask '" + mask + "' --json");
    CHECK(bare.exit_code == 1);
    // A moved sidecar mask path: found beside the sidecar's folder, or checked without design.
    fs::remove(dir.path / "clear" / "m.export.json");
    const auto none = run_cli("check '" + (dir / "clear") + "/m.gds' --json");
    CHECK(none.exit_code == 0);
}

// PINMASK_TIME_LIMIT: a budget that is not spent changes nothing; a spent one (1 us, the
// smallest accepted: spent before the first poll on any machine) stops the check of a mask
// and of a fabrication file with exit code 3 and no verdict, text or JSON, naming the limit.
TEST_CASE("check: a spent PINMASK_TIME_LIMIT stops with exit code 3 and prints no verdict") {
    TempDir dir("check-time");
    const std::string mask =
        write_mask(dir, "m.mask.json", make_mask(16, {{0, 0}, {3, 5}, {8, 2}, {12, 12}}, 2));
    REQUIRE(run_cli("export '" + mask + "' --format gds --no-psf -o '" + (dir / "fab") + "'")
                .exit_code == 0);
    const std::string gds = dir / "fab/m.gds";
    const auto free = run_cli("check --json " + gds);
    ::setenv("PINMASK_TIME_LIMIT", "2m", 1);
    const auto roomy = run_cli("check --json " + gds);
    ::setenv("PINMASK_TIME_LIMIT", "1e-6", 1);
    std::vector<test::CliResult> spent;
    for (const std::string& input : {mask, gds})
        for (const std::string json : {"", "--json "})
            spent.push_back(run_cli("check " + json + input));
    ::unsetenv("PINMASK_TIME_LIMIT");
    INFO(free.err);
    REQUIRE(free.exit_code == 0);
    CHECK(roomy.exit_code == 0);
    CHECK(roomy.out == free.out);
    for (const auto& r : spent) {
        INFO(r.err);
        CHECK(r.exit_code == 3);
        CHECK(r.out.empty());
        CHECK(r.err.find("pinmask: stopped: the time limit PINMASK_TIME_LIMIT = 1e-06 s was "
                         "spent: check stopped") != std::string::npos);
        CHECK(r.err.find("no verdict (exit code 3)") != std::string::npos);
    }
}

TEST_CASE("check with vendor none: no design rules given, none checked, not \"clean\"") {
    TempDir dir("check-none");
    const auto mask =
        write_mask(dir, "m.mask.json", make_mask(16, {{0, 0}, {0, 2}, {3, 5}, {8, 8}}, 2));
    const auto text = run_cli("check --vendor none " + mask);
    INFO(text.err);
    CHECK(text.exit_code == 0);
    CHECK(text.out.find("result      no design rules given: none checked") != std::string::npos);
    CHECK(text.out.find("result      clean") == std::string::npos);
    const auto r = run_cli("check --json --vendor none " + mask);
    REQUIRE(r.exit_code == 0);
    CHECK(json_of(r)["design_rules_checked"] == false);
    const auto film = run_cli("check --json --vendor film " + mask);
    REQUIRE(film.exit_code == 0);
    CHECK(json_of(film)["design_rules_checked"] == true);
}
