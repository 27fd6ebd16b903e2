#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// A mask file in the format of io/mask_json (written by hand so the test does not depend on
// the codec's writer).
std::string mask_json(int n, const std::vector<std::pair<int, int>>& holes, int tiles,
                      double spacing, bool violations_allowed) {
    std::string h;
    for (const auto& [r, c] : holes)
        h += (h.empty() ? "" : ", ") + std::string("[") + std::to_string(r) + ", " +
             std::to_string(c) + "]";
    return R"({"format": "pinmask-mask", "version": 1,
 "pattern": {"n": )" +
           std::to_string(n) + R"(, "pinholes": [)" + h + R"(], "tiles": [)" +
           std::to_string(tiles) + ", " + std::to_string(tiles) + R"(], "min_spacing_cells": )" +
           std::to_string(spacing) + R"(},
 "optics": {"object_distance_m": 6.0, "lens_focal_m": 0.12, "sensor_distance_m": 0.055,
            "wavelength_m": 5.5e-07, "pixel_pitch_m": 3e-05, "pinhole_m": 0.00044,
            "sensor_px": [720, 480]},
 "psf": {"kernel": {"model": "auto"}, "pixels_per_cell": 8},
 "provenance": {"seed": 1, "generator": "test", "family": "random",
                "spacing_violations_allowed": )" +
           (violations_allowed ? "true" : "false") + "}}\n";
}

// The golden 4 x 4 mask of tests/export (pinholes (0,0), (1,2), (3,2), one tile).
std::string golden_mask_file(const TempDir& dir) {
    const std::string path = dir / "golden4x4.mask.json";
    std::ofstream(path) << mask_json(4, {{0, 0}, {1, 2}, {3, 2}}, 1, 2.0, false);
    return path;
}

std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> out;
    if (!fs::exists(dir)) return out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST_CASE("export writes every format plus a sidecar, and the SVG matches the golden file") {
    TempDir dir("export");
    const std::string mask = golden_mask_file(dir);
    const auto r = run_cli("export '" + mask + "' -o '" + (dir / "out") + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(names_in(dir.path / "out") ==
          std::vector<std::string>{"golden4x4.dxf", "golden4x4.export.json", "golden4x4.gbr",
                                   "golden4x4.gds", "golden4x4.pdf", "golden4x4.png",
                                   "golden4x4.psf.json", "golden4x4.psf.tiff", "golden4x4.svg"});
    const std::string golden = std::string(PINMASK_SOURCE_DIR) + "/tests/export/golden/";
    CHECK(slurp(dir / "out/golden4x4.svg") == slurp(golden + "golden4x4.svg"));
    CHECK(slurp(dir / "out/golden4x4.dxf") == slurp(golden + "golden4x4.dxf"));
    CHECK(slurp(dir / "out/golden4x4.gbr") == slurp(golden + "golden4x4.gbr"));
    const auto side = nlohmann::json::parse(slurp(dir / "out/golden4x4.export.json"));
    CHECK(side["format"] == "pinmask-export");
    CHECK(side["mask"]["geometry_hash"] == "8929e0407826140f");
    CHECK(side["geometry"]["tone"] == "clear");
    CHECK(side["geometry"]["mirrored"] == false);
    CHECK(side["psf"]["files"].size() == 2);
    const auto psf = nlohmann::json::parse(slurp(dir / "out/golden4x4.psf.json"));
    CHECK(psf["mask_geometry_hash"] == "8929e0407826140f");
    REQUIRE(side["files"].size() == 6);
    for (const auto& f : side["files"]) {
        const std::string name = f["name"];
        CHECK(f["bytes"].get<std::size_t>() == fs::file_size(dir.path / "out" / name));
        if (name.ends_with(".pdf") || name.ends_with(".png"))  // pictures: read back too
            CHECK(f["verification"].get<std::string>().starts_with("read back"));
        else
            CHECK(f["verification"] == "read back: 3 polygons identical to the design");
    }
}

TEST_CASE("export is deterministic and every option combination reads back exactly") {
    TempDir dir("export-det");
    const std::string mask = golden_mask_file(dir);
    const std::string opts =
        " --tone dark --mirror --marks --label --frame 0.2mm --shape circle --chord-tol 50nm "
        "--max-vertices 40 --dpi 600";
    const auto a = run_cli("export '" + mask + "' -o '" + (dir / "a") + "'" + opts);
    const auto b = run_cli("export '" + mask + "' -o '" + (dir / "b") + "'" + opts + " --json");
    INFO(a.err << b.err);
    REQUIRE(a.exit_code == 0);
    REQUIRE(b.exit_code == 0);
    for (const std::string& name : names_in(dir.path / "a"))
        CHECK(slurp(dir / ("a/" + name)) == slurp(dir / ("b/" + name)));
    const auto side = nlohmann::json::parse(b.out);
    CHECK(side["geometry"]["tone"] == "dark");
    CHECK(side["geometry"]["mirrored"] == true);
    CHECK(side["geometry"]["annotations"].get<int>() > 4);
    for (const auto& f : side["files"]) {  // every format is read back, pictures included
        CHECK(f["verification"].get<std::string>().find("not readable") == std::string::npos);
        CHECK(f["verification"].get<std::string>().starts_with("read back"));
    }
}

TEST_CASE("touching pinholes (spacing rule off) are merged; a failed check writes nothing") {
    TempDir dir("export-mura");
    const std::string mask = dir / "dense.mask.json";
    std::ofstream(mask) << mask_json(5, {{0, 0}, {0, 1}, {1, 1}, {3, 3}, {4, 4}}, 2, 0.0, true);
    // Diagonal neighbours touch at a corner: the export fails (exit 1, as check's), names the
    // rule and writes nothing, with or without --require-drc-clean (the default).
    for (const std::string flags : {"", " --require-drc-clean"}) {
        const std::string out = dir / ("strict" + std::to_string(flags.size()));
        const auto strict = run_cli("export '" + mask + "'" + flags + " -o '" + out + "'");
        INFO(flags << ": " << strict.err);
        CHECK(strict.exit_code == 1);
        CHECK(strict.err.find("found violations: touching ") != std::string::npos);
        CHECK(strict.err.find("nothing is written (--write-on-violations") != std::string::npos);
        CHECK(names_in(out).empty());
    }
    // --write-on-violations: the files are written for inspection, the violations said, and the
    // exit code is 1 all the same.
    const auto r = run_cli("export '" + mask + "' --format gds,svg --no-psf --json " +
                           "--write-on-violations -o '" + (dir / "o") + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 1);
    CHECK(r.err.find("found violations") != std::string::npos);
    const auto side = nlohmann::json::parse(r.out);
    CHECK(side["geometry"]["polygons"].get<int>() < 5 * 4);
    CHECK(names_in(dir.path / "o") ==
          std::vector<std::string>{"dense.export.json", "dense.gds", "dense.svg"});
    // The two contradict each other: refused before any work.
    const auto both = run_cli("export '" + mask + "' --require-drc-clean --write-on-violations " +
                              "-o '" + (dir / "both") + "'");
    CHECK(both.exit_code == 2);
    CHECK(both.err.find("--write-on-violations") != std::string::npos);
    CHECK(names_in(dir.path / "both").empty());
}

TEST_CASE("touching pinholes that break the spacing rule fail export and check, merged or not") {
    // (0, 0) and (0, 1) touch: the layout merges them into one polygon, whose centroid the
    // polygon-level spacing rule cannot see; the rule is applied to the design's pinholes first.
    TempDir dir("export-merged-spacing");
    const std::string mask = dir / "close.mask.json";
    std::ofstream(mask) << mask_json(5, {{0, 0}, {0, 1}, {3, 3}}, 2, 2.0, true);
    const auto e =
        run_cli("export '" + mask + "' --format gds --no-psf --write-on-violations -o '" +
                (dir / "o") + "'");
    CHECK(e.exit_code == 1);
    CHECK((e.out + e.err).find("pinholes (0, 0) and (0, 1) of the design") != std::string::npos);
    for (const std::string& input : {mask, (dir.path / "o" / "close.gds").string()}) {
        const auto c = run_cli("check '" + input + "'");
        INFO(input << "\n" << c.out << c.err);
        CHECK(c.exit_code == 1);
        CHECK(c.out.find("spacing 1") != std::string::npos);
    }
}

TEST_CASE("bad input: exit 2 and no files") {
    TempDir dir("export-bad");
    const std::string mask = golden_mask_file(dir);
    const std::string out = dir / "out";
    for (const std::string& flags :
         {"--tone grey", "--format svg,tiff", "--shape star", "--grid 1.5nm", "--frame -1mm",
          "--dpi 0", "--chord-tol 0", "--layer 70000 --format gds"}) {
        const auto r = run_cli("export '" + mask + "' -o '" + out + "' " + flags);
        INFO(flags << ": " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(names_in(out).empty());
    }
    CHECK(run_cli("export '" + (dir / "missing.mask.json") + "' -o '" + out + "'").exit_code == 2);
    const std::string empty = dir / "empty.mask.json";
    std::ofstream(empty) << mask_json(4, {}, 1, 2.0, false);
    const auto e = run_cli("export '" + empty + "' -o '" + out + "'");
    CHECK(e.exit_code == 2);
    CHECK(e.err.find("empty") != std::string::npos);
    CHECK(names_in(out).empty());
}

TEST_CASE("export --help and bench export --help teach the flags with an example") {
    const auto h = run_cli("export --help");
    CHECK(h.exit_code == 0);
    for (const char* flag :
         {"--format", "--tone", "--mirror", "--marks", "--label", "--frame", "--shape",
          "--chord-tol", "--grid", "--layer", "--datatype", "--dpi", "Example"})
        CHECK(h.out.find(flag) != std::string::npos);
    const auto b = run_cli("bench export --help");
    CHECK(b.exit_code == 0);
    CHECK(b.out.find("reference") != std::string::npos);
}

TEST_CASE("bench export runs and reports ratios (small mask)") {
    const auto r = run_cli("bench export --n 64 --repeat 1 --json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["pinholes"].get<int>() > 300);
    CHECK(j["records"].size() == 13);  // layout, 7 writes, 5 reads
    for (const auto& rec : j["records"]) CHECK(rec["ratio"].get<double>() > 0);
    // Data volume: the 16^2 x 4 x 4 tiled mask as hierarchical GDSII and as OASIS is several
    // times smaller than flat GDSII (the 1024^2-cell figure is in docs/benchmarks.md). Records: one
    // tile, uniform random, tiled.
    REQUIRE(j["sizes"].size() == 3);
    CHECK(j["sizes"][1]["mask"].get<std::string>().find("uniform") != std::string::npos);
    const auto& tiled = j["sizes"][2];
    CHECK(tiled["flat_gds_bytes"].get<double>() > 3 * tiled["cells_gds_bytes"].get<double>());
    CHECK(tiled["flat_gds_bytes"].get<double>() > 5 * tiled["oasis_bytes"].get<double>());
}

TEST_CASE("export --vendor: list, the film-plotter preset (DXF mm + 1-bit TIFF), flags win") {
    TempDir dir("export-vendor");
    const std::string mask = golden_mask_file(dir);
    const auto list = run_cli("export '" + mask + "' --vendor list");
    CHECK(list.exit_code == 0);
    for (const char* name : {"chrome-photomask", "film-plotter", "gerber-film", "laser-cutter"})
        CHECK(list.out.find(name) != std::string::npos);
    const auto r = run_cli("export '" + mask + "' --vendor film-plotter --no-psf --label -o '" +
                           (dir / "film") + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(names_in(dir.path / "film") ==
          std::vector<std::string>{"golden4x4.dxf", "golden4x4.export.json", "golden4x4.tif"});
    const auto side = nlohmann::json::parse(slurp(dir / "film/golden4x4.export.json"));
    CHECK(side["geometry"]["unit"] == "mm");
    CHECK(side["geometry"]["emulsion"] == "down");
    CHECK(side["geometry"]["frame_m"].get<double>() == 2e-3);
    CHECK(slurp(dir / "film/golden4x4.dxf").find("$INSUNITS\n 70\n4\n") != std::string::npos);
    // TIFF: little-endian, 1 bit per sample, 25400 dpi in the resolution tags (RATIONAL
    // 25400/1 as libtiff writes it) and a width of extent / 1 um.
    const std::string tif = slurp(dir / "film/golden4x4.tif");
    CHECK(tif.starts_with("II*"));
    CHECK(side["files"][1]["detail"] == "25400.000000 dpi");
    // Flags win over the preset.
    const auto w = run_cli("export '" + mask + "' --vendor film-plotter --units um --format dxf " +
                           "--emulsion up --no-psf -o '" + (dir / "um") + "'");
    INFO(w.err);
    REQUIRE(w.exit_code == 0);
    const auto side2 = nlohmann::json::parse(slurp(dir / "um/golden4x4.export.json"));
    CHECK(side2["geometry"]["unit"] == "um");
    CHECK(side2["geometry"]["emulsion"] == "up");
    CHECK(side2["files"].size() == 1);
    // The positive/negative words and the emulsion side appear on the label and in the output.
    const auto t = run_cli("export '" + mask + "' --format svg --tone positive --emulsion down " +
                           "--no-psf -o '" + (dir / "pos") + "'");
    CHECK(t.exit_code == 0);
    CHECK(t.out.find("dark (positive)") != std::string::npos);
    CHECK(t.out.find("emulsion down") != std::string::npos);
}
