// design/optics/working_distance: the pinhole for N whole pixels per cell AT u, the usable
// object-distance range against a direct evaluation of the tolerance, both pinhole optima, and the
// edge cases.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "design/optics/working_distance.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// d = 345.0 um is the reference value to four digits: +-0.1 %.
constexpr double kQuotedRel = 1e-3;
// Closed forms evaluated two ways in double: a few ulps of ~1e-16 each.
constexpr double kExactRel = 1e-12;

// A machine-vision camera: 3.45 um pixels, 2448 x 2048, 25 mm lens, sensor 20 mm behind,
// u = 2 m, 530 nm.
Camera fine_pixel_camera() {
    Camera c;
    c.pixel_pitch_m = 3.45e-6;
    c.sensor_cols = 2448;
    c.sensor_rows = 2048;
    c.lens_focal_m = 0.025;
    c.sensor_distance_m = 0.020;
    c.object_distance_m = 2.0;
    c.wavelength_m = 530e-9;
    c.pinhole_m = 300e-6;
    return c;
}

// The tolerance written out for the test: pitch error across s_max = n d between u' and u, px.
double pitch_error_px(const Camera& c, int n, double u_prime) {
    auto inv = [](double x) { return std::isinf(x) ? 0.0 : 1.0 / x; };
    const double pitch = [&](double u) {
        return c.pinhole_m *
               (1.0 - c.sensor_distance_m / c.lens_focal_m + c.sensor_distance_m * inv(u)) /
               c.pixel_pitch_m;
    }(u_prime);
    const double at_u = c.pinhole_m *
                        (1.0 - c.sensor_distance_m / c.lens_focal_m +
                         c.sensor_distance_m * inv(c.object_distance_m)) /
                        c.pixel_pitch_m;
    return n * std::fabs(pitch - at_u);
}

}  // namespace

TEST_CASE("3.45 um camera: 21 px per cell at 2 m needs d = 345.0 um; the range matches the rule") {
    Camera c = fine_pixel_camera();
    c.pinhole_m = pinhole_for_pixels_per_cell(c, 21);
    CHECK(std::fabs(c.pinhole_m / 345.0e-6 - 1.0) <= kQuotedRel);
    const PatternGeometry g{16, 20, 2, 2};
    const WorkingDistance wd = compute_working_distance(c, g, {1.0, 21});
    CHECK_CLOSE(wd.pixels_per_cell_at_u, 21.0, kExactRel);
    CHECK(wd.lsi_mismatch_px <= 1e-9);
    CHECK_CLOSE(wd.period_px, 16 * 21.0, kExactRel);
    // Both ends sit exactly on the tolerance; just inside passes, just outside fails.
    CHECK_CLOSE(pitch_error_px(c, 16, wd.range_near_m), 1.0, 1e-9);
    REQUIRE(std::isfinite(wd.range_far_m));
    CHECK_CLOSE(pitch_error_px(c, 16, wd.range_far_m), 1.0, 1e-9);
    CHECK(pitch_error_px(c, 16, wd.range_near_m * 1.01) < 1.0);
    CHECK(pitch_error_px(c, 16, wd.range_near_m * 0.99) > 1.0);
    CHECK(pitch_error_px(c, 16, wd.range_far_m * 0.99) < 1.0);
    CHECK(pitch_error_px(c, 16, wd.range_far_m * 1.01) > 1.0);
    CHECK(wd.range_near_m < 2.0);
    CHECK(wd.range_far_m > 2.0);
    // A looser tolerance reaches infinity.
    const WorkingDistance loose = compute_working_distance(c, g, {50.0, 21});
    CHECK(std::isinf(loose.range_far_m));
}

TEST_CASE("both pinhole optima, the with-lens one at z_eff(u)") {
    Camera c = fine_pixel_camera();
    const WorkingDistance wd = compute_working_distance(c, {16, 20, 2, 2});
    CHECK(std::fabs(wd.optimum_pinhole_lensless_m - 160.6e-6) <= 0.05e-6);  // reference: 160.6 um
    const double z_u = 1.0 / (1.0 / 0.020 - 1.0 / 0.025 + 1.0 / 2.0);
    CHECK_CLOSE(wd.optimum_pinhole_with_lens_m, 1.56 * std::sqrt(530e-9 * z_u), kExactRel);
    c.object_distance_m = kInf;  // the reference "about 359 um" is the distant-object value
    const WorkingDistance far = compute_working_distance(c, {16, 20, 2, 2});
    CHECK(std::fabs(far.optimum_pinhole_with_lens_m - 359e-6) <= 0.5e-6);
    // At the lensless optimum, the with-lens Fresnel number is ~0.12 and spots cover ~4 cells.
    c.pinhole_m = far.optimum_pinhole_lensless_m;
    const WorkingDistance small = compute_working_distance(c, {16, 20, 2, 2});
    CHECK(std::fabs(small.fresnel_number_with_lens_at_u - 0.12) <= 0.005);
    CHECK(small.spot_spread_cells > 3.5);
    CHECK(small.spreads_beyond_cell());
    c.pinhole_m = far.optimum_pinhole_with_lens_m;
    CHECK_FALSE(compute_working_distance(c, {16, 20, 2, 2}).spreads_beyond_cell());
}

TEST_CASE("edge cases: f = f' at infinity, object inside the focal length, empty tolerance") {
    Camera c = paper_camera();
    c.lens_focal_m = c.sensor_distance_m;
    c.object_distance_m = kInf;
    const WorkingDistance wd = compute_working_distance(c, {16, 20, 2, 2});
    CHECK(std::isinf(wd.optimum_pinhole_with_lens_m));
    CHECK(std::isinf(wd.pinhole_for_pixels_per_cell_m));
    try {
        pinhole_for_pixels_per_cell(c, 8);
        FAIL("accepted");
    } catch (const InvalidInput& e) {
        CHECK(std::string(e.what()).find("z_eff is infinite") != std::string::npos);
    }
    c.object_distance_m = 6.0;  // a finite u: M = f/u, the solve is defined again
    CHECK(std::isfinite(pinhole_for_pixels_per_cell(c, 8)));
    Camera inside = paper_camera();
    inside.object_distance_m = 0.1;  // f' = 120 mm
    CHECK_THROWS_AS(compute_working_distance(inside, {16, 20, 2, 2}), InvalidInput);
    CHECK_THROWS_AS(compute_working_distance(paper_camera(), {16, 20, 2, 2}, {0.0, 0}),
                    InvalidInput);
    CHECK_THROWS_AS(compute_working_distance(paper_camera(), {16, 20, 2, 2}, {NAN, 0}),
                    InvalidInput);
    CHECK_THROWS_AS(pinhole_for_pixels_per_cell(paper_camera(), 0), InvalidInput);
}

TEST_CASE("paper: 8 px at 6 m, mismatch against the 8-px model, near end clamps at f'") {
    const WorkingDistance wd = compute_working_distance(paper_camera(), {16, 20, 2, 2});
    CHECK(wd.pixels_per_cell == 8);
    CHECK(std::fabs(wd.pixels_per_cell_at_u - 8.08) <= 0.005);  // design.md 2: 8.08 pixels
    CHECK_CLOSE(wd.lsi_mismatch_px, 16 * (wd.pixels_per_cell_at_u - 8.0), kExactRel);
    const WorkingDistance huge =
        compute_working_distance(paper_camera(), {16, 20, 2, 2}, {1000, 0});
    CHECK(huge.range_near_clamped_to_focal);
    CHECK(huge.range_near_m == paper_camera().lens_focal_m);
}

// pitch(u) = d |1 - f/f' + f/u| / w computed here by hand (not by pixels_per_cell_at): below half
// a pixel the nearest whole number is 0 and every whole-pixel model would use 1, so it is said.
TEST_CASE("cells under half a pixel are named, with the fields that set the pitch") {
    Camera c = paper_camera();  // f' 120 mm, f 55 mm, u 6 m, d 440 um, w 30 um: 8.1 px per cell
    CHECK_FALSE(sub_pixel_cells(c).has_value());
    c.lens_focal_m = 0.055;  // f' = f: M(6 m) = f/u = 0.00917, 0.134 px per cell
    const double pitch = c.pinhole_m * std::fabs(1.0 - 0.055 / 0.055 + 0.055 / 6.0) / 30e-6;
    CHECK(pitch == doctest::Approx(0.1344).epsilon(1e-3));
    const auto why = sub_pixel_cells(c);
    REQUIRE(why.has_value());
    CHECK(why->find("0.134 px") != std::string::npos);
    for (const char* field : {"lens_focal_m", "sensor_distance_m", "pinhole_m", "pixel_pitch_m"})
        CHECK(why->find(field) != std::string::npos);
    // f = f' with u = inf: magnification 0, the case kernel_validity reports; not this one.
    c.object_distance_m = INFINITY;
    CHECK_FALSE(sub_pixel_cells(c).has_value());
    // Just above half a pixel rounds to 1 honestly: d chosen for 0.6 px at u = 6 m.
    c = paper_camera();
    c.pinhole_m = 0.6 * c.pixel_pitch_m / std::fabs(1.0 - 0.055 / 0.12 + 0.055 / 6.0);
    CHECK_FALSE(sub_pixel_cells(c).has_value());
    c.pinhole_m *= 0.4 / 0.6;
    CHECK(sub_pixel_cells(c).has_value());
    // A second camera (3.45 um pixels): 0.3 px per cell is said, 0.7 px is not.
    Camera m = fine_pixel_camera();
    const double mag = std::fabs(1.0 - m.sensor_distance_m / m.lens_focal_m +
                                 m.sensor_distance_m / m.object_distance_m);
    m.pinhole_m = 0.3 * m.pixel_pitch_m / mag;
    CHECK(sub_pixel_cells(m).has_value());
    m.pinhole_m = 0.7 * m.pixel_pitch_m / mag;
    CHECK_FALSE(sub_pixel_cells(m).has_value());
}
