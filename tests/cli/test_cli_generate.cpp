// `pinmask generate` end to end: the documented command, byte-identical reruns, refusals with exit
// code 2 and no file, the families and the recorded configuration.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "design/pattern/mask.hpp"
#include "io/mask_json.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;

namespace {

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("generate: the documented command writes a mask that reads back") {
    TempDir dir("gen");
    const std::string out = dir / "m.mask.json";
    const auto r = run_cli(
        "generate --family random --grid 16 --holes 20 --spacing 2 --tiles 2 --seed 7 -o " + out);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const Mask m = io::read_mask_file(out);
    CHECK(m.pattern.n == 16);
    CHECK(m.pattern.pinholes.size() == 20);
    CHECK(m.pattern.tiles_rows == 2);
    CHECK(m.pattern.tiles_cols == 2);
    CHECK(m.pattern.min_spacing_cells == 2.0);
    CHECK(spacing_violations(m.pattern).empty());
    CHECK(m.provenance.seed == 7);
    CHECK(m.provenance.family == "random");
    CHECK_FALSE(m.provenance.spacing_violations_allowed);
    CHECK(m.psf.pixels_per_cell == 8);  // round(0.44 mm (1 - 55/120) / 30 um) = round(7.94)
    CHECK(m.psf.kernel.model == "auto");
    CHECK(m.camera.pinhole_m == 440e-6);
    CHECK(has(r.out, geometry_hash(m)));
    // Rewriting what was read reproduces the file byte for byte.
    io::write_mask_file(dir / "again.mask.json", m);
    CHECK(slurp(out) == slurp(dir / "again.mask.json"));
}

TEST_CASE("generate: same seed, byte-identical file; another seed, another pattern") {
    TempDir dir("gen-seed");
    const std::string base = "generate --grid 31 --holes 40 --spacing 2.5 --seed 11 -o ";
    REQUIRE(run_cli(base + (dir / "a.mask.json")).exit_code == 0);
    REQUIRE(run_cli(base + (dir / "b.mask.json")).exit_code == 0);
    CHECK(slurp(dir / "a.mask.json") == slurp(dir / "b.mask.json"));
    REQUIRE(
        run_cli("generate --grid 31 --holes 40 --spacing 2.5 --seed 12 -o " + (dir / "c.mask.json"))
            .exit_code == 0);
    CHECK(io::read_mask_file(dir / "a.mask.json").pattern.pinholes !=
          io::read_mask_file(dir / "c.mask.json").pattern.pinholes);
}

TEST_CASE("generate --json: machine-readable summary only") {
    TempDir dir("gen-json");
    const auto r = run_cli("generate --family paper --seed 3 --json -o " + (dir / "p.mask.json"));
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j.at("path") == dir / "p.mask.json");
    CHECK(j.at("n") == 16);
    CHECK(j.at("holes") == 20);
    CHECK(j.at("family") == "paper");
    CHECK(j.at("spacing_violations") == 0);
    CHECK(j.at("geometry_hash") == geometry_hash(io::read_mask_file(dir / "p.mask.json")));
}

TEST_CASE("generate: infeasible and invalid requests exit 2, name the rule, write nothing") {
    TempDir dir("gen-bad");
    const std::string out = dir / "x.mask.json";
    const auto refused = [&](const std::string& args, const std::string& message) {
        const auto r = run_cli("generate " + args + " -o " + out);
        INFO(args);
        INFO(r.err);
        CHECK(r.exit_code == 2);
        CHECK(has(r.err, message));
        CHECK_FALSE(std::filesystem::exists(out));
        CHECK(std::filesystem::is_empty(dir.path));
    };
    refused("--grid 16 --holes 80 --spacing 2", "At most 64 fit");
    refused("--grid 16 --holes 80 --spacing 2", "a verified lattice placement holds 64");
    refused("--family ura", "rectangular");
    refused("--family hadamard", "must be one of random, paper, mura");
    refused("--family mura --grid 15 --allow-violations", "prime order p = 4m + 1");
    refused("--family mura --grid 13", "--allow-violations");
    refused("--family mura --grid 13 --holes 20 --allow-violations", "84 pinholes");
    refused("--family paper --grid 32", "the paper family fixes");
    refused("--pixels-per-cell 0", "--pixels-per-cell = 0: must be >= 1");
    // f = f' with the paper's 440 um (--preset keeps it; without it the camera would get the
    // whole-pixel optimum, 3.27 mm for 1 px per cell, and be legal).
    refused("--preset paper --lens-focal 55mm", "give --pixels-per-cell explicitly");
    refused("--kernel measured", "needs --kernel-path");
    refused("--kernel gauss", "gauss");
    refused("--pinhole -1mm", "pinhole_m = -1 mm: must be finite and > 0");
    const auto r = run_cli("generate -o " + (dir / "no-such-dir/x.mask.json"));
    CHECK(r.exit_code == 2);
    CHECK(has(r.err, "output directory does not exist"));
}

TEST_CASE("generate: mura with permission, and the camera flags are recorded") {
    TempDir dir("gen-mura");
    const auto r = run_cli("generate --family mura --grid 13 --allow-violations -o " +
                           (dir / "mura.mask.json"));
    REQUIRE(r.exit_code == 0);
    const Mask m = io::read_mask_file(dir / "mura.mask.json");
    CHECK(m.pattern.n == 13);
    CHECK(m.pattern.pinholes.size() == 84);  // (13^2 - 1) / 2
    CHECK(m.provenance.spacing_violations_allowed);
    CHECK(m.provenance.family == "mura");
    CHECK(m.provenance.seed == 0);  // a MURA does not depend on the seed
    REQUIRE(run_cli("generate --family mura --grid 13 --allow-violations --seed 9 -o " +
                    (dir / "mura9.mask.json"))
                .exit_code == 0);
    CHECK(slurp(dir / "mura.mask.json") == slurp(dir / "mura9.mask.json"));
    // At spacing 1 a MURA meets the rule and needs no permission.
    REQUIRE(run_cli("generate --family mura --grid 5 --spacing 1 -o " + (dir / "m1.mask.json"))
                .exit_code == 0);
    CHECK_FALSE(io::read_mask_file(dir / "m1.mask.json").provenance.spacing_violations_allowed);

    REQUIRE(run_cli("generate --lens-focal inf --object-distance inf --pinhole 443um "
                    "--kernel fresnel --seed 5 -o " +
                    (dir / "c.mask.json"))
                .exit_code == 0);
    const Mask c = io::read_mask_file(dir / "c.mask.json");
    CHECK(std::isinf(c.camera.lens_focal_m));
    CHECK(std::isinf(c.camera.object_distance_m));
    CHECK(c.camera.pinhole_m == doctest::Approx(443e-6).epsilon(1e-12));
    CHECK(c.psf.kernel.model == "fresnel");
    CHECK(c.psf.pixels_per_cell == 15);  // no lens: round(443 um / 30 um) = round(14.77)
}

TEST_CASE("generate --help teaches the flags and shows the example") {
    const auto r = run_cli("generate --help");
    CHECK(r.exit_code == 0);
    CHECK(has(r.out, "--allow-violations"));
    CHECK(has(r.out, "--pixels-per-cell"));
    CHECK(has(r.out, "Example: pinmask generate --family random --grid 16 --holes 20"));
    CHECK(has(r.out, "no separate configuration file"));
}
