// The mask file codec: round trips, deterministic bytes, and every class of malformed file
// rejected with the key path and the rule.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/errors/error.hpp"
#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using doctest::Contains;
using pinmask::io::mask_file_text;
using pinmask::io::mask_from_json;
using pinmask::io::mask_to_json;
using pinmask::io::MaskReadOptions;
using pinmask::io::read_mask_file;
using pinmask::io::write_mask_file;

namespace {

Mask sample_mask() {
    Mask m;
    m.pattern.n = 16;
    // Deliberately unsorted: the writer puts pinholes in canonical order.
    m.pattern.pinholes = {{5, 9}, {0, 0}, {15, 2}, {0, 13}, {8, 8}};
    m.camera = paper_camera();
    m.psf.pixels_per_cell = 8;
    m.psf.kernel.model = "fresnel";
    m.psf.kernel.wavelengths = {{450e-9, 0.25}, {550e-9, 0.5}, {650e-9, 0.25}};
    m.provenance.seed = 18446744073709551615ULL;  // the full uint64 range survives
    m.provenance.generator = "test";
    m.provenance.family = "random";
    m.provenance.scores = {{"sidelobe_ratio", 0.125}, {"mse_db", -31.5}};
    return m;
}

void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

}  // namespace

TEST_CASE("mask round trip: every field survives, pinholes come back sorted") {
    test::TempDir dir("maskjson");
    const Mask m = sample_mask();
    write_mask_file(dir / "a.mask.json", m);
    const Mask r = read_mask_file(dir / "a.mask.json");
    CHECK(r.pattern.n == 16);
    CHECK(r.pattern.pinholes == sorted_pinholes(m.pattern));
    CHECK(r.pattern.tiles_rows == 2);
    CHECK(r.pattern.tiles_cols == 2);
    CHECK(r.pattern.min_spacing_cells == 2.0);
    // Doubles are written in shortest round-trip form: exact equality is the contract.
    CHECK(r.camera.object_distance_m == m.camera.object_distance_m);
    CHECK(r.camera.lens_focal_m == m.camera.lens_focal_m);
    CHECK(r.camera.sensor_distance_m == m.camera.sensor_distance_m);
    CHECK(r.camera.wavelength_m == m.camera.wavelength_m);
    CHECK(r.camera.pixel_pitch_m == m.camera.pixel_pitch_m);
    CHECK(r.camera.pinhole_m == m.camera.pinhole_m);
    CHECK(r.camera.sensor_cols == 720);
    CHECK(r.camera.sensor_rows == 480);
    CHECK(r.psf.pixels_per_cell == 8);
    CHECK(r.psf.kernel.model == "fresnel");
    CHECK(r.psf.kernel.wavelengths == m.psf.kernel.wavelengths);
    CHECK(r.provenance.seed == m.provenance.seed);
    CHECK(r.provenance.generator == "test");
    CHECK(r.provenance.family == "random");
    CHECK(r.provenance.scores == m.provenance.scores);
    CHECK_FALSE(r.provenance.spacing_violations_allowed);
    CHECK(geometry_hash(r) == geometry_hash(m));
    // Writing what was read gives the same bytes; the pinhole order in memory does not matter.
    write_mask_file(dir / "b.mask.json", r);
    CHECK(test::slurp(dir / "a.mask.json") == test::slurp(dir / "b.mask.json"));
}

TEST_CASE("file layout: fixed key order, one pinhole per line, infinite distances as \"inf\"") {
    Mask m = sample_mask();
    m.camera.object_distance_m = INFINITY;
    m.camera.lens_focal_m = INFINITY;
    const std::string text = mask_file_text(m);
    const auto at = [&](const char* s) { return text.find(s); };
    CHECK(at("\"format\"") < at("\"version\""));
    CHECK(at("\"version\"") < at("\"pattern\""));
    CHECK(at("\"pattern\"") < at("\"optics\""));
    CHECK(at("\"optics\"") < at("\"psf\""));
    CHECK(at("\"psf\"") < at("\"provenance\""));
    CHECK(at("\"n\"") < at("\"pinholes\""));
    CHECK(text.find("\"pinholes\": [\n      [0, 0],\n      [0, 13],") != std::string::npos);
    CHECK(text.find("\"object_distance_m\": \"inf\"") != std::string::npos);
    CHECK(text.find("\"lens_focal_m\": \"inf\"") != std::string::npos);
    CHECK(text.find("\"geometry_hash\": \"" + geometry_hash(m) + "\"") != std::string::npos);
    const Mask r = mask_from_json(nlohmann::json::parse(text));
    CHECK(std::isinf(r.camera.object_distance_m));
    CHECK(std::isinf(r.camera.lens_focal_m));
    CHECK(text.back() == '\n');
}

TEST_CASE("the camera's band: carried in optics, refused beside an explicit wavelength list") {
    Mask m = sample_mask();
    m.psf.kernel.wavelengths.clear();
    m.camera.bandwidth_m = 40e-9;
    const std::string text = mask_file_text(m);
    CHECK(text.find("\"bandwidth_m\": 4e-08") != std::string::npos);
    CHECK(mask_from_json(nlohmann::json::parse(text)).camera.bandwidth_m == 40e-9);
    nlohmann::json both = nlohmann::json::parse(text);
    both["psf"]["kernel"]["wavelengths"] = {{540e-9, 1.0}, {560e-9, 1.0}};
    CHECK_THROWS_WITH_AS(mask_from_json(both), Contains("optics.bandwidth_m"), InvalidInput);
    CHECK_THROWS_WITH_AS(mask_from_json(both), Contains("psf.kernel.wavelengths"), InvalidInput);
    // A mask without the key (every file from before it) reads as one wavelength.
    CHECK(mask_from_json(mask_to_json(sample_mask())).camera.bandwidth_m == 0.0);
    CHECK(mask_file_text(sample_mask()).find("bandwidth") == std::string::npos);
}

TEST_CASE("reading rejects each malformed field with its key path and rule") {
    const nlohmann::json good = mask_to_json(sample_mask());
    CHECK_NOTHROW(mask_from_json(good));
    const auto rejects = [&](auto edit, const char* message) {
        nlohmann::json j = good;
        edit(j);
        CHECK_THROWS_WITH_AS(mask_from_json(j), Contains(message), InvalidInput);
    };
    rejects([](auto& j) { j["format"] = "other"; }, "format: \"other\" is not \"pinmask-mask\"");
    rejects([](auto& j) { j["version"] = 2; }, "version: 2 is not supported");
    rejects([](auto& j) { j["pattern"]["holes"] = 1; }, "pattern.holes: unknown key");
    rejects([](auto& j) { j["extra"] = 1; }, "extra: unknown key");
    rejects([](auto& j) { j["provenance"]["scores"] = 1; }, "provenance.scores: must be an object");
    rejects([](auto& j) { j["psf"]["kernel"].erase("model"); },
            "psf.kernel.model: missing required key");
    rejects([](auto& j) { j["pattern"]["n"] = "16"; }, "pattern.n: must be an integer");
    rejects([](auto& j) { j["pattern"]["n"] = 16.5; }, "pattern.n: must be an integer");
    rejects([](auto& j) { j["pattern"]["n"] = 5000; }, "pattern.n: 5000 must be between 1 and");
    rejects(
        [](auto& j) {
            j["pattern"]["pinholes"][0] = {1, 2, 3};
        },
        "pattern.pinholes[0]: must be a two-element array");
    rejects(
        [](auto& j) {
            j["pattern"]["pinholes"][2] = {16, 3};
        },
        "pattern.pinholes[2] = (16, 3): outside the 16 x 16 grid");
    rejects([](auto& j) { j["pattern"]["pinholes"][1] = j["pattern"]["pinholes"][0]; },
            "duplicate pinhole");
    rejects(
        [](auto& j) {
            j["pattern"]["pinholes"].push_back({1, 1});
        },
        "pattern.min_spacing_cells = 2");
    rejects([](auto& j) { j["pattern"]["tiles"] = {0, 2}; }, "pattern.tiles = 0x2");
    rejects([](auto& j) { j["optics"]["pinhole_m"] = -1e-3; }, "optics.pinhole_m");
    rejects([](auto& j) { j["optics"]["lens_focal_m"] = "infinite"; },
            "optics.lens_focal_m: must be a number or the string \"inf\"");
    rejects([](auto& j) { j["optics"]["pixel_pitch_m"] = INFINITY; },
            "optics.pixel_pitch_m: must be a finite number");
    rejects([](auto& j) { j["optics"]["sensor_px"] = {720}; },
            "optics.sensor_px: must be a two-element array [cols, rows]");
    rejects([](auto& j) { j["psf"]["pixels_per_cell"] = 0; },
            "psf.pixels_per_cell: 0 must be >= 1");
    rejects([](auto& j) { j["psf"]["kernel"]["model"] = "gauss"; }, "is not a kernel model");
    rejects([](auto& j) { j["psf"]["kernel"]["model"] = "measured"; },
            "needs a non-empty measured_path");
    rejects([](auto& j) { j["psf"]["kernel"]["measured_path"] = "k.tif"; },
            "only used with model \"measured\"");
    rejects(
        [](auto& j) {
            j["psf"]["kernel"]["wavelengths"][0] = {-1e-9, 1.0};
        },
        "psf.kernel.wavelengths[0][0]: wavelength must be > 0");
    rejects([](auto& j) { j["provenance"]["seed"] = -1; },
            "provenance.seed: must be a non-negative");
    rejects([](auto& j) { j["provenance"]["spacing_violations_allowed"] = 1; },
            "must be true or false");
    // Moving a pinhole without updating the hash: the file was edited inconsistently.
    rejects([](auto& j) { j["pattern"]["pinholes"][0] = {3, 3}; }, "provenance.geometry_hash: \"");
    rejects([](auto& j) { j["optics"]["pinhole_m"] = 441e-6; }, "does not match the geometry");
}

TEST_CASE("an edit is accepted when the hash key is removed; spacing violations by permission") {
    nlohmann::json j = mask_to_json(sample_mask());
    j["provenance"].erase("geometry_hash");
    j["pattern"]["pinholes"][0] = {3, 3};
    CHECK(mask_from_json(j).pattern.pinholes[0] == Cell{0, 13});  // sorted: (3,3) is not first
    j["pattern"]["pinholes"].push_back({1, 14});                  // diagonal neighbour of (0, 13)
    CHECK_THROWS_AS(mask_from_json(j), InvalidInput);
    MaskReadOptions allow;
    allow.allow_spacing_violations = true;
    CHECK(mask_from_json(j, allow).pattern.pinholes.size() == 6);
    j["provenance"]["spacing_violations_allowed"] = true;
    CHECK(mask_from_json(j).pattern.pinholes.size() == 6);
}

TEST_CASE("file-level errors name the file: syntax with position, duplicate keys, overflow") {
    test::TempDir dir("maskjson-bad");
    const std::string good = mask_file_text(sample_mask());

    write_text(dir / "syntax.mask.json",
               "{\n  \"format\": \"pinmask-mask\",\n  \"version\": 1,,\n}");
    CHECK_THROWS_WITH_AS(read_mask_file(dir / "syntax.mask.json"),
                         Contains("syntax.mask.json: invalid JSON (byte "), InvalidInput);
    CHECK_THROWS_WITH_AS(read_mask_file(dir / "syntax.mask.json"), Contains("line 3"),
                         InvalidInput);

    std::string dup = good;
    dup.replace(dup.find("\"n\": 16"), 7, "\"n\": 16, \"n\": 16");
    write_text(dir / "dup.mask.json", dup);
    CHECK_THROWS_WITH_AS(read_mask_file(dir / "dup.mask.json"),
                         Contains("dup.mask.json: pattern.n: duplicate key"), InvalidInput);

    // A literal too large for a double is a parse error (nlohmann out_of_range.406).
    std::string big = good;
    const auto pos = big.find("\"pixel_pitch_m\": ") + 17;
    big.replace(pos, big.find(',', pos) - pos, "1e999");
    write_text(dir / "big.mask.json", big);
    CHECK_THROWS_WITH_AS(read_mask_file(dir / "big.mask.json"),
                         Contains("big.mask.json: invalid JSON: number overflow"), InvalidInput);

    // Pinholes are checked as they stream out of the parser: same key paths and rules.
    const auto with_pinhole = [&](const std::string& name, const std::string& element) {
        std::string t = good;
        t.replace(t.find("[5, 9]"), 6, element);
        write_text(dir / name, t);
        return dir / name;
    };
    CHECK_THROWS_WITH_AS(read_mask_file(with_pinhole("p1.mask.json", "[5, \"a\"]")),
                         Contains("pattern.pinholes[2][1]: must be an integer"), InvalidInput);
    CHECK_THROWS_WITH_AS(read_mask_file(with_pinhole("p2.mask.json", "[5, 9, 1]")),
                         Contains("pattern.pinholes[2]: must be a two-element array"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(read_mask_file(with_pinhole("p3.mask.json", "7")),
                         Contains("pattern.pinholes[2]: must be a two-element array"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(read_mask_file(with_pinhole("p4.mask.json", "[5, 10000000000]")),
                         Contains("pattern.pinholes[2][1]: 10000000000 is out of range"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(read_mask_file(with_pinhole("p5.mask.json", "{\"a\": 1, \"a\": 2}")),
                         Contains("pattern.pinholes[2].a: duplicate key"), InvalidInput);
    CHECK_THROWS_WITH_AS(read_mask_file(with_pinhole("p6.mask.json", "[0, 13]")),
                         Contains("pattern.pinholes[2] = (0, 13): duplicate pinhole"),
                         InvalidInput);

    CHECK_THROWS_WITH_AS(read_mask_file(dir / "missing.mask.json"),
                         Contains("missing.mask.json: cannot read mask file"), InvalidInput);
    write_text(dir / "array.mask.json", "[1, 2]");
    CHECK_THROWS_WITH_AS(read_mask_file(dir / "array.mask.json"),
                         Contains("(root): must be an object"), InvalidInput);
}

TEST_CASE("writing an invalid mask throws and leaves no file") {
    test::TempDir dir("maskjson-write");
    Mask m = sample_mask();
    m.pattern.pinholes.push_back({1, 1});  // neighbour of (0, 0), violations not allowed
    CHECK_THROWS_WITH_AS(write_mask_file(dir / "bad.mask.json", m), Contains("refusing to write"),
                         InvalidInput);
    CHECK_FALSE(std::filesystem::exists(dir / "bad.mask.json"));
    CHECK(std::filesystem::is_empty(dir.path));
    m.provenance.spacing_violations_allowed = true;
    write_mask_file(dir / "ok.mask.json", m);
    CHECK(read_mask_file(dir / "ok.mask.json").provenance.spacing_violations_allowed);
}
