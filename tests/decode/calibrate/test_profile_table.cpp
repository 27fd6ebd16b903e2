// decode/calibrate/profile_table against the test's own diffraction integral
// (point_source_model.hpp): the pixel-integrated profile of a square pinhole at several offsets,
// for the Fresnel numbers of the camera matrix, and the box's closed form.
#include <doctest/doctest.h>

#include "decode/calibrate/profile_table.hpp"
#include "design/optics/optics.hpp"
#include "tests/decode/calibrate/camera_matrix.hpp"

using namespace pinmask;

namespace {

// int_{x-1/2}^{x+1/2} a h(a t) dt by Simpson over 64 intervals (the test's own integral).
double pixel_value(const test::PinholeProfile1d& h, double a, double x) {
    constexpr int m = 64;
    double acc = 0.0;
    for (int k = 0; k <= m; ++k) {
        const double t = x - 0.5 + double(k) / m;
        const double w = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        acc += w * a * h(a * t);
    }
    return acc / (3.0 * m);
}

}  // namespace

TEST_CASE("profile table: the pixel-integrated diffraction profile of the camera matrix") {
    for (const char* name : {"paper", "c-mount", "nir"}) {
        CAPTURE(name);
        const test::CameraCase c = test::camera_case(name);
        const Camera& k = c.camera;
        const double a = k.pinhole_m * k.pixel_pitch_m / (k.wavelength_m * k.sensor_distance_m);
        const test::PinholeProfile1d h(fresnel_number_at_u(k));
        const calibrate::ProfileTable q(k, KernelModel::kFresnel, k.pinhole_m, 6.0 * c.ppc);
        double sum = 0.0;
        for (int x = -6 * c.ppc; x <= 6 * c.ppc; ++x) sum += q.value(x);
        CHECK(sum == doctest::Approx(q.enclosed()).epsilon(1e-3));
        for (double x : {0.0, 0.3, 1.7, 0.5 * c.ppc, 1.0 * c.ppc, 2.5 * c.ppc + 0.25}) {
            CAPTURE(x);
            const double ref = pixel_value(h, a, x);
            CHECK(q.value(x) == doctest::Approx(ref).epsilon(2e-3).scale(1e-6));
        }
    }
}
