// design/optics/image_plane: the thin lens' image distance and the first zero of one pinhole's
// Fraunhofer spot, against numbers written out here and, for the first zero, against the zero
// of the sinc^2 field computed at z_eff and magnified onto the sensor (a second path).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "design/optics/camera.hpp"
#include "design/optics/image_plane.hpp"

using namespace pinmask;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The first zero through the effective distance: sinc^2(pi d x / (lambda z_eff)) vanishes first
// at x = lambda |z_eff| / d on the plane at z_eff, and the lens maps that plane onto the sensor
// with magnification |M| = f / |z_eff|; in pixels of pitch w.
double first_zero_via_z_eff(const Camera& c) {
    const double inv_fl = std::isinf(c.lens_focal_m) ? 0.0 : 1.0 / c.lens_focal_m;
    const double inv_u = std::isinf(c.object_distance_m) ? 0.0 : 1.0 / c.object_distance_m;
    const double z_eff = 1.0 / std::fabs(1.0 / c.sensor_distance_m - inv_fl + inv_u);
    const double x = c.wavelength_m * z_eff / c.pinhole_m;
    const double m = c.sensor_distance_m / z_eff;
    return x * m / c.pixel_pitch_m;
}

}  // namespace

TEST_CASE("image distance: 1/v = 1/f' - 1/u, f' at infinity, none without a lens") {
    // Paper: 1/v = 1/0.12 - 1/6 -> v = 0.72 / 5.88 = 122.449 mm.
    CHECK(image_distance_at_u_m(paper_camera()) ==
          doctest::Approx(0.12 * 6.0 / (6.0 - 0.12)).epsilon(1e-12));
    Camera far = paper_camera();
    far.object_distance_m = kInf;
    CHECK(image_distance_at_u_m(far) == 0.12);
    Camera lensless = paper_camera();
    lensless.lens_focal_m = kInf;
    CHECK(std::isinf(image_distance_at_u_m(lensless)));
    // A phone-like lens (f' = 4.3 mm) at 1 m: v = 4.3 / (1 - 0.0043) mm.
    Camera phone = paper_camera();
    phone.lens_focal_m = 4.3e-3;
    phone.object_distance_m = 1.0;
    CHECK(image_distance_at_u_m(phone) == doctest::Approx(4.3e-3 / (1.0 - 4.3e-3)).epsilon(1e-12));
}

TEST_CASE("diffraction first zero: lambda f / (d w) px, the same at every u and f'") {
    // Paper: 550 nm x 55 mm / (440 um x 30 um) = 2.2917 px.
    CHECK(diffraction_first_zero_px(paper_camera()) ==
          doctest::Approx(2.2916666666666667).epsilon(1e-12));
    Camera cameras[4] = {paper_camera(), paper_camera(), paper_camera(), paper_camera()};
    cameras[1].lens_focal_m = kInf;  // lensless
    cameras[2].object_distance_m = 0.5;
    cameras[3].pixel_pitch_m = 1.4e-6;  // phone-like
    cameras[3].lens_focal_m = 4.3e-3;
    cameras[3].sensor_distance_m = 4.0e-3;
    cameras[3].pinhole_m = 266e-6;
    cameras[3].object_distance_m = 1.0;
    for (const Camera& c : cameras) {
        CAPTURE(c.lens_focal_m);
        CAPTURE(c.object_distance_m);
        CHECK(diffraction_first_zero_px(c) ==
              doctest::Approx(first_zero_via_z_eff(c)).epsilon(1e-12));
    }
}
