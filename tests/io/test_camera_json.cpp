// io/camera_json: round trip, infinities, and refusal of malformed files naming the key.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/error.hpp"
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
