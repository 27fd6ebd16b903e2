// decode/depthmap/depthmap_planes against the closed forms written here: the design's usable
// range 1/u' = 1/u +- w / (f n d) (one pixel of pitch change across one period), one pixel of
// pattern change across the tiled mask w / (f N_t d), and the count of planes one resolvable step
// apart; the refusals of an end given on the wrong side of the defaulted one.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/errors/error.hpp"
#include "decode/depthmap/depthmap_planes.hpp"
#include "design/pattern/mask.hpp"
#include "optimize/metrics/depth_fisher.hpp"

using namespace pinmask;

namespace {

// The machine-vision camera of docs/depth.md at 0.5 m, 8 x 8 cells, 2 x 2 tiles, box spots.
Mask mv_mask() {
    Mask m;
    m.camera.pixel_pitch_m = 3.45e-6;
    m.camera.sensor_cols = m.camera.sensor_rows = 160;
    m.camera.lens_focal_m = 0.025;
    m.camera.sensor_distance_m = 0.020;
    m.camera.object_distance_m = 0.5;
    m.camera.wavelength_m = 530e-9;
    m.camera.pinhole_m = 115e-6;
    m.pattern.n = 8;
    m.pattern.tiles_rows = m.pattern.tiles_cols = 2;
    m.pattern.pinholes = {{0, 0}, {2, 5}, {5, 2}, {6, 6}};
    m.pattern.min_spacing_cells = 2.0;
    m.psf.pixels_per_cell = 8;
    m.psf.kernel.model = "box";
    return m;
}

}  // namespace

TEST_CASE("depthmap_planes: the design's usable range and planes one resolvable step apart") {
    const Mask m = mv_mask();
    const DepthmapPlaneChoice c = choose_depthmap_planes(m, {}, {}, {}, 160, 160);
    const double w = 3.45e-6, f = 0.020, d = 115e-6;
    const double lsi = w / (f * 8 * d);  // one pixel across one period (8 cells), in 1/u
    CHECK(c.from_m == doctest::Approx(1.0 / (2.0 + lsi)).epsilon(1e-12));
    CHECK(c.to_m == doctest::Approx(1.0 / (2.0 - lsi)).epsilon(1e-12));
    CHECK_FALSE(c.from_given);
    CHECK_FALSE(c.steps_given);
    const double px = w / (f * 16 * d);  // one pixel across the tiled mask (16 cells)
    CHECK(c.one_pixel_inverse_per_m == doctest::Approx(px).epsilon(1e-12));
    DepthFisherOptions fo;
    fo.photons = kDepthmapResolutionPhotons;
    fo.rows = fo.cols = 160;
    const double crb = 2.355 * depth_fisher(m, 0.5, fo).crb_inverse_per_m;
    CHECK(c.crb_distance_m == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(c.crb_fwhm_inverse_per_m == doctest::Approx(crb).epsilon(1e-9));
    const double step = std::max(px, crb);
    CHECK(c.resolvable_inverse_per_m == doctest::Approx(step).epsilon(1e-9));
    // The range spans 2 lsi = 4 px of pattern change: 5 planes when the pixel is the step.
    CHECK(c.steps == static_cast<int>(std::ceil(2.0 * lsi / step - 1e-9)) + 1);
    CHECK(c.spacing_inverse_per_m <= step * (1.0 + 1e-9));
    CHECK(c.resolution_near_m == doctest::Approx(c.from_m * c.from_m * step).epsilon(1e-9));
    CHECK(c.resolution_far_m == doctest::Approx(c.to_m * c.to_m * step).epsilon(1e-9));
    CHECK_FALSE(c.capped);
    CHECK_FALSE(c.finer_than_resolvable);
}

TEST_CASE("depthmap_planes: given ends and counts are kept; a wide range is capped at 64") {
    const Mask m = mv_mask();
    const DepthmapPlaneChoice g = choose_depthmap_planes(m, 0.4, 2.0, 7, 160, 160);
    CHECK(g.from_m == 0.4);
    CHECK(g.to_m == 2.0);
    CHECK(g.steps == 7);
    CHECK(g.steps_given);
    CHECK(g.spacing_inverse_per_m == doctest::Approx((2.5 - 0.5) / 6).epsilon(1e-12));
    CHECK(g.finer_than_resolvable == (g.spacing_inverse_per_m < g.resolvable_inverse_per_m));
    // 64 planes over 0.45 .. 0.55 m are 0.0064 /m apart, far below one pixel (0.094 /m).
    CHECK(choose_depthmap_planes(m, 0.45, 0.55, 64, 160, 160).finer_than_resolvable);
    // 0.15 m .. inf is 6.67 /m, 71 one-pixel steps of 0.094 /m: capped.
    const DepthmapPlaneChoice wide =
        choose_depthmap_planes(m, 0.15, std::numeric_limits<double>::infinity(), {}, 160, 160);
    CHECK(wide.steps == kDepthmapMaxDefaultPlanes);
    CHECK(wide.capped);
    CHECK(std::isinf(wide.resolution_far_m));
    // One end given, the other from the design.
    const DepthmapPlaneChoice near_only = choose_depthmap_planes(m, 0.45, {}, {}, 160, 160);
    CHECK(near_only.from_m == 0.45);
    CHECK(near_only.to_m == doctest::Approx(1.0 / (2.0 - 3.45e-6 / (0.02 * 8 * 115e-6))));
}

TEST_CASE("depthmap_planes refuses an end on the wrong side of the design's other end") {
    const Mask m = mv_mask();
    CHECK_THROWS_WITH_AS(choose_depthmap_planes(m, 2.0, {}, {}, 160, 160),
                         doctest::Contains("from_m"), InvalidInput);
    CHECK_THROWS_WITH_AS(choose_depthmap_planes(m, {}, 0.3, {}, 160, 160),
                         doctest::Contains("to_m"), InvalidInput);
    CHECK_THROWS_WITH_AS(choose_depthmap_planes(m, 0.4, 2.0, 1, 160, 160),
                         doctest::Contains("steps"), InvalidInput);
    CHECK_THROWS_WITH_AS(choose_depthmap_planes(m, 0.01, 2.0, 3, 160, 160),
                         doctest::Contains("focal length"), InvalidInput);
}
