// design/optics/default_pinhole: a camera given without a pinhole gets the whole-pixel pinhole
// nearest its diffraction optimum, checked against the closed forms written out here (the optimum
// 1.56 sqrt(lambda |z_eff(u)|) and d = N w / |M(u)|) on a matrix of cameras; a solve far from
// the optimum is said.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "design/optics/camera.hpp"
#include "design/optics/default_pinhole.hpp"

using namespace pinmask;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Camera camera(double u, double fl, double f, double lambda, double w) {
    Camera c = paper_camera();
    c.object_distance_m = u;
    c.lens_focal_m = fl;
    c.sensor_distance_m = f;
    c.wavelength_m = lambda;
    c.pixel_pitch_m = w;
    return c;
}

double inv(double x) { return std::isinf(x) ? 0.0 : 1.0 / x; }

}  // namespace

TEST_CASE("no pinhole given: the whole-pixel pinhole nearest the optimum, on a matrix of cameras") {
    const Camera cameras[] = {
        paper_camera(),
        camera(1.0, 4.3e-3, 4.0e-3, 550e-9, 1.4e-6),  // phone-like
        camera(2.0, 25e-3, 20e-3, 530e-9, 3.45e-6),   // machine vision
        camera(1.2, 75e-3, 45e-3, 850e-9, 5.86e-6),   // near infrared
        camera(kInf, kInf, 5e-3, 550e-9, 2.2e-6),     // lensless, distant object
        camera(0.3, kInf, 2e-3, 450e-9, 1.0e-6),      // lensless, near object
        camera(6.0, 0.12, 0.2, 550e-9, 30e-6),        // past focus (f > f')
    };
    for (const Camera& c : cameras) {
        CAPTURE(c.sensor_distance_m);
        CAPTURE(c.pixel_pitch_m);
        validate(c);
        const double inv_z =
            std::fabs(1.0 / c.sensor_distance_m - inv(c.lens_focal_m) + inv(c.object_distance_m));
        const double m = std::fabs(1.0 - c.sensor_distance_m * inv(c.lens_focal_m) +
                                   c.sensor_distance_m * inv(c.object_distance_m));
        const double optimum = 1.56 * std::sqrt(c.wavelength_m / inv_z);
        const double n_opt = std::max(1.0, std::round(optimum * m / c.pixel_pitch_m));
        const DefaultPinhole d = default_pinhole(c);
        REQUIRE(d.solved);
        CHECK(d.optimum_m == doctest::Approx(optimum).epsilon(1e-12));
        CHECK(static_cast<double>(d.pixels_per_cell) == n_opt);
        // On the 1 nm grid: within half a nanometre of N w / |M|, and a whole number of nm.
        CHECK(std::fabs(d.pinhole_m - n_opt * c.pixel_pitch_m / m) <= 0.5e-9 + 1e-15);
        CHECK(std::fabs(d.pinhole_m * 1e9 - std::round(d.pinhole_m * 1e9)) < 1e-6);
        // Within half a pixel per cell of the optimum's pitch, unless one pixel is already more.
        // (the 1 nm snap moves the pitch by far less than 1e-3 px on these cameras)
        if (n_opt > 1) CHECK(std::fabs(d.pinhole_m - optimum) * m / c.pixel_pitch_m <= 0.5 + 1e-3);
        CHECK(d.note.find("`pinhole_m`") != std::string::npos);
        Camera chosen = c;
        chosen.pinhole_m = d.pinhole_m;
        validate(chosen);
    }
}

TEST_CASE(
    "no finite optimum (f = f' with u = inf): the camera's pinhole is kept and that is said") {
    const Camera c = camera(kInf, 55e-3, 55e-3, 550e-9, 30e-6);
    const DefaultPinhole d = default_pinhole(c);
    CHECK_FALSE(d.solved);
    CHECK(d.pinhole_m == c.pinhole_m);
    CHECK(std::isinf(d.optimum_m));
    CHECK(d.note.find("no finite optimum") != std::string::npos);
}

TEST_CASE("a solve starting far from the optimum says where the optimum is") {
    // Lensless at f = 5 mm, u = 6 m: the optimum is 1.56 sqrt(lambda z), z = 1/(1/f + 1/u),
    // about 82 um; the paper's 440 um is 5.4x that.
    Camera c = camera(6.0, kInf, 5e-3, 550e-9, 30e-6);
    const double z = 1.0 / (1.0 / 5e-3 + 1.0 / 6.0);
    const double optimum = 1.56 * std::sqrt(550e-9 * z);
    c.pinhole_m = 440e-6;
    const std::string far = far_from_optimum_note(c);
    CHECK(far.find("x the diffraction optimum") != std::string::npos);
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3g", 440e-6 / optimum);
    CHECK(far.find(std::string(ratio) + "x") != std::string::npos);
    // Within a factor of 2 either way: nothing to say.
    c.pinhole_m = 1.9 * optimum;
    CHECK(far_from_optimum_note(c).empty());
    c.pinhole_m = optimum / 1.9;
    CHECK(far_from_optimum_note(c).empty());
    c.pinhole_m = optimum / 2.1;
    CHECK_FALSE(far_from_optimum_note(c).empty());
}
