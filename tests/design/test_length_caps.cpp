// A length typed without its unit is metres, so `--pinhole 300` is a 300 m pinhole: validate
// refuses every length above its quantity's physical range, naming the field and the unit the
// number most likely meant; values at the cap and every real camera pass.
#include <doctest/doctest.h>

#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "design/optics/camera.hpp"

using namespace pinmask;

namespace {

std::string refusal(const Camera& c) {
    try {
        validate(c);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

struct Case {
    const char* field;
    double Camera::*member;
    double typed;           // the number as typed without a unit (metres)
    const char* suggested;  // the spelling the message must suggest
};

}  // namespace

TEST_CASE("a length far above its quantity's range is refused with the unit it probably meant") {
    const Case cases[] = {
        {"pinhole_m", &Camera::pinhole_m, 300, "did you mean 300um?"},
        {"pinhole_m", &Camera::pinhole_m, 0.44, "did you mean 0.44mm?"},
        {"pinhole_m", &Camera::pinhole_m, 440000, "did you mean 440000nm?"},
        {"pixel_pitch_m", &Camera::pixel_pitch_m, 30, "did you mean 30um?"},
        {"pixel_pitch_m", &Camera::pixel_pitch_m, 3.45, "did you mean 3.45um?"},
        {"wavelength_m", &Camera::wavelength_m, 550, "did you mean 550nm?"},
        {"wavelength_m", &Camera::wavelength_m, 0.85, "did you mean 0.85um?"},
        {"sensor_distance_m", &Camera::sensor_distance_m, 55, "did you mean 55mm?"},
        {"lens_focal_m", &Camera::lens_focal_m, 120, "did you mean 120mm?"},
    };
    for (const Case& k : cases) {
        CAPTURE(k.field);
        CAPTURE(k.typed);
        Camera c = paper_camera();
        c.*k.member = k.typed;
        // The lens-to-sensor distance stays below the focal length it is tested beside.
        if (k.member == &Camera::lens_focal_m) c.object_distance_m = 1e3;
        const std::string what = refusal(c);
        CHECK(what.rfind(std::string(k.field) + " = ", 0) == 0);
        CHECK(what.find("a number without a unit is in metres") != std::string::npos);
        CHECK(what.find(k.suggested) != std::string::npos);
    }
}

TEST_CASE("lengths at their caps, and real cameras, pass") {
    Camera at_caps = paper_camera();
    at_caps.pinhole_m = 10e-3;
    at_caps.pixel_pitch_m = 1e-3;
    at_caps.wavelength_m = 100e-6;
    at_caps.sensor_distance_m = 10.0;
    at_caps.lens_focal_m = std::numeric_limits<double>::infinity();
    CHECK(refusal(at_caps).empty());
    at_caps.lens_focal_m = 10.0;
    at_caps.sensor_distance_m = 5.0;
    at_caps.object_distance_m = 100.0;
    CHECK(refusal(at_caps).empty());
    // A phone camera, a machine-vision camera with a 25 mm lens, a lensless near-infrared one.
    Camera phone = paper_camera();
    phone.pixel_pitch_m = 1.4e-6;
    phone.lens_focal_m = 4.3e-3;
    phone.sensor_distance_m = 4.0e-3;
    phone.pinhole_m = 20e-6;
    phone.object_distance_m = 1.0;
    CHECK(refusal(phone).empty());
    Camera vision = paper_camera();
    vision.pixel_pitch_m = 3.45e-6;
    vision.lens_focal_m = 25e-3;
    vision.sensor_distance_m = 20e-3;
    vision.pinhole_m = 345e-6;
    vision.object_distance_m = 2.0;
    CHECK(refusal(vision).empty());
    Camera nir = paper_camera();
    nir.lens_focal_m = std::numeric_limits<double>::infinity();
    nir.wavelength_m = 850e-9;
    nir.bandwidth_m = 30e-9;
    nir.sensor_distance_m = 5e-3;
    nir.pinhole_m = 100e-6;
    CHECK(refusal(nir).empty());
}

TEST_CASE("a number beyond every unit's reach is refused asking for the unit") {
    Camera c = paper_camera();
    c.pinhole_m = 5e5;  // as nm, 0.5 mm: a pinhole
    CHECK(refusal(c).find("did you mean 500000nm?") != std::string::npos);
    c = paper_camera();
    c.wavelength_m = 5e5;  // 0.5 mm as nm, 0.5 m as um: no unit makes it light
    const std::string what = refusal(c);
    CHECK(what.find("wavelength_m = ") == 0);
    CHECK(what.find("give the length with its unit") != std::string::npos);
    CHECK(what.find("did you mean") == std::string::npos);
}
