// design/psf/psf_exact: spot centroids against an independent Eq. (3) computation, area resampling
// keeps the sum, the integer model is reproduced when the pitch is a whole number, edge cases.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

// The required bound on a spot centroid against its Eq. (3) position.
constexpr double kCentroidTolPx = 0.05;
// Sums of a few thousand products of normalised values.
constexpr double kSumTol = 1e-12;

// 20 pinholes 3 cells apart (also across the seam: 12 -> 16 is 4), so box spots never touch.
Mask spaced_mask() {
    Mask m;
    m.pattern.n = 16;
    m.pattern.min_spacing_cells = 2.0;
    for (int a = 0; a < 5; ++a) {
        for (int b = 0; b < 4; ++b) m.pattern.pinholes.push_back({3 * a, 3 * b + 1});
    }
    m.camera = paper_camera();
    m.psf.pixels_per_cell = 8;
    m.psf.kernel.model = "box";
    return m;
}

// Eq. (3) written out for the test: q = (1 - f/f' + f/u) s, s from the mask centre.
double expected_centre(const Mask& m, double u, int window, int cell) {
    const Camera& c = m.camera;
    const double mag = 1.0 - c.sensor_distance_m / c.lens_focal_m + c.sensor_distance_m / u;
    const double s_m = (cell + 0.5 - m.pattern.n * m.pattern.tiles_rows / 2.0) * c.pinhole_m;
    return window / 2.0 + mag * s_m / c.pixel_pitch_m;
}

}  // namespace

TEST_CASE("exact geometry at 6 m: every spot centroid within 0.05 px of Eq. (3)") {
    const Mask m = spaced_mask();
    const double u = 6.0;
    ExactPsfOptions o;
    o.object_distance_m = u;
    const Plane a = exact_psf(m, o);
    REQUIRE(a.rows() == m.camera.sensor_rows);
    REQUIRE(a.cols() == m.camera.sensor_cols);
    CHECK(std::fabs(a.sum() - 4.0) <= kSumTol);  // 2 x 2 tiles, each period sums to 1
    const double pitch = 8.08;  // docs/design.md 2: paper at 6 m (window half-size)
    int spots = 0;
    for (int tr = 0; tr < 2; ++tr) {
        for (int tc = 0; tc < 2; ++tc) {
            for (const Cell& cell : m.pattern.pinholes) {
                const double y = expected_centre(m, u, int(a.rows()), tr * 16 + cell.row);
                const double x = expected_centre(m, u, int(a.cols()), tc * 16 + cell.col);
                double s = 0, sy = 0, sx = 0;
                for (int r = int(y - 1.5 * pitch); r <= int(y + 1.5 * pitch); ++r) {
                    for (int c = int(x - 1.5 * pitch); c <= int(x + 1.5 * pitch); ++c) {
                        s += a(r, c);
                        sy += a(r, c) * (r + 0.5);
                        sx += a(r, c) * (c + 0.5);
                    }
                }
                CHECK(std::fabs(s - 1.0 / 20) <= kSumTol);
                CHECK(std::fabs(sy / s - y) <= kCentroidTolPx);
                CHECK(std::fabs(sx / s - x) <= kCentroidTolPx);
                ++spots;
            }
        }
    }
    CHECK(spots == 80);
}

TEST_CASE("exact geometry with a whole-pixel pitch tiles the integer model") {
    Mask m = spaced_mask();
    m.camera.object_distance_m = std::numeric_limits<double>::infinity();
    m.camera.lens_focal_m = std::numeric_limits<double>::infinity();  // M = 1: pitch d / w
    m.camera.pinhole_m = 8 * m.camera.pixel_pitch_m;                  // exactly 8 px per cell
    ExactPsfOptions o;
    o.object_distance_m = m.camera.object_distance_m;
    o.rows = o.cols = 256;  // the 2 x 2 tiled mask exactly
    const Plane exact = exact_psf(m, o);
    const Plane one = mask_psf(m);  // 128 x 128, kernel centred in its cell
    double worst = 0;
    for (int r = 0; r < 256; ++r) {
        for (int c = 0; c < 256; ++c) {
            worst = std::max(worst, std::fabs(exact(r, c) - one(r % 128, c % 128)));
        }
    }
    // Box spots of exactly one cell never reach the window edge or wrap: equal to rounding.
    CHECK(worst <= kSumTol);
}

TEST_CASE("exact geometry: edge cases refused") {
    Mask m = spaced_mask();
    ExactPsfOptions o;
    o.object_distance_m = 0.1;  // inside f' = 120 mm
    CHECK_THROWS_AS(exact_psf(m, o), InvalidInput);
    o.object_distance_m = 6.0;
    o.rows = -1;
    CHECK_THROWS_AS(exact_psf(m, o), InvalidInput);
    o.rows = 0;
    m.pattern.pinholes.clear();
    CHECK_THROWS_AS(exact_psf(m, o), InvalidInput);
}

TEST_CASE("a measured kernel wider than the period is refused, naming both sizes") {
    Mask m = spaced_mask();
    m.pattern.n = 4;
    m.pattern.pinholes = {{0, 0}, {2, 2}};
    m.psf.pixels_per_cell = 2;  // period 8 px
    const Plane big = Plane::Constant(9, 9, 1.0);
    test::TempDir dir("wide-kernel");
    const std::string path = dir / "k.npy";
    write_image(path, Image(big));
    m.psf.kernel.model = "measured";
    m.psf.kernel.measured_path = path;
    try {
        mask_kernel(m);
        FAIL("accepted");
    } catch (const InvalidInput& e) {
        CHECK(std::string(e.what()).find("exceeds the period of 8 x 8") != std::string::npos);
    }
}
