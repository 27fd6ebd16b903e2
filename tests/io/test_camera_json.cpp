// io/camera_json: round trip, infinities, and refusal of malformed files naming the key.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "io/camera_json.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
namespace fs = std::filesystem;

namespace {

std::string refusal(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
    try {
        io::read_camera_file(path);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "accepted";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("camera file: round trip (doubles exact, inf kept), malformed files refused") {
    test::TempDir dir("camera-json");
    Camera c = paper_camera();
    c.object_distance_m = std::numeric_limits<double>::infinity();
    c.pinhole_m = 345.00000000000004e-6;
    c.sensor_cols = 2448;
    io::write_camera_file(dir / "a.camera.json", c);
    const Camera back = io::read_camera_file(dir / "a.camera.json");
    CHECK(std::isinf(back.object_distance_m));
    CHECK(back.pinhole_m == c.pinhole_m);  // shortest round-trip printing: exact
    CHECK(back.sensor_cols == 2448);
    CHECK(back.lens_focal_m == c.lens_focal_m);

    const std::string good = io::camera_file_text(paper_camera());
    CHECK(refusal(dir / "b.json", "{").find("invalid JSON") != std::string::npos);
    CHECK(
        refusal(dir / "c.json", replaced(good, "pinmask-camera", "pinmask-mask")).find("format") !=
        std::string::npos);
    CHECK(refusal(dir / "d.json", replaced(good, "\"version\": 1", "\"version\": 2"))
              .find("version") != std::string::npos);
    CHECK(refusal(dir / "e.json", replaced(good, "\"version\"", "\"colour\": 1, \"version\""))
              .find("colour") != std::string::npos);
    CHECK(refusal(dir / "f.json",
                  replaced(good, "\"pixel_pitch_m\": 3e-05", "\"pixel_pitch_m\": -3e-05"))
              .find("pixel_pitch_m") != std::string::npos);
    CHECK_THROWS_AS(io::read_camera_file(dir / "missing.camera.json"), InvalidInput);
}

TEST_CASE("camera file: the band round-trips; files without it read 0 and are written unchanged") {
    test::TempDir dir("camera-band");
    Camera c = paper_camera();
    c.wavelength_m = 850e-9;
    c.bandwidth_m = 30e-9;
    io::write_camera_file(dir / "band.camera.json", c);
    const std::string text = test::slurp(dir / "band.camera.json");
    CHECK(text.find("\"bandwidth_m\": 3e-08") != std::string::npos);
    CHECK(io::read_camera_file(dir / "band.camera.json").bandwidth_m == c.bandwidth_m);

    // A monochromatic camera writes no bandwidth key: the bytes of files from before the band.
    const std::string mono = io::camera_file_text(paper_camera());
    CHECK(mono.find("bandwidth") == std::string::npos);
    std::ofstream(dir / "old.camera.json") << mono;
    const Camera old = io::read_camera_file(dir / "old.camera.json");
    CHECK(old.bandwidth_m == 0.0);
    CHECK(io::camera_file_text(old) == mono);

    // Not physical: refused naming the key.
    for (const std::string bad : {"-3e-08", "5e-07", "\"wide\""}) {
        CAPTURE(bad);
        const std::string edited =
            replaced(text, "\"bandwidth_m\": 3e-08", "\"bandwidth_m\": " + bad);
        const std::string why = refusal(dir / "bad.json", edited);
        INFO(why);
        CHECK(why.find("bandwidth_m") != std::string::npos);
    }
}
