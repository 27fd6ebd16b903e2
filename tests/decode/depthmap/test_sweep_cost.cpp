// decode/depthmap/sweep_cost against a second path written here: the residual capture - h (*) x by
// a direct cyclic convolution sum in the pixel domain (the PSF's centre floor(size/2) at the
// origin, as deconvwnr), its box mean by direct sums, on a small capture.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/errors/error.hpp"
#include "decode/depthmap/sweep_cost.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/psf_exact.hpp"

using namespace pinmask;

namespace {

Mask small_mask() {
    Mask m;
    m.camera.pixel_pitch_m = 3.45e-6;
    m.camera.sensor_cols = m.camera.sensor_rows = 24;
    m.camera.lens_focal_m = 0.025;
    m.camera.sensor_distance_m = 0.020;
    m.camera.object_distance_m = 0.5;
    m.camera.wavelength_m = 530e-9;
    m.camera.pinhole_m = 28.75e-6;  // 2 px per cell at 0.5 m
    m.pattern.n = 4;
    m.pattern.tiles_rows = m.pattern.tiles_cols = 2;
    m.pattern.pinholes = {{0, 0}, {1, 2}, {3, 1}};
    m.pattern.min_spacing_cells = 2.0;
    m.psf.pixels_per_cell = 2;
    m.psf.kernel.model = "box";
    return m;
}

}  // namespace

TEST_CASE("sweep_cost's residual energy equals the direct cyclic residual of its estimate") {
    const Mask m = small_mask();
    const int r = 24, c = 20;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    Plane capture(r, c);
    for (Eigen::Index i = 0; i < capture.size(); ++i) capture.data()[i] = uni(rng);
    const double u = 0.8, nsr = 0.05;
    const int window = 5;
    const PlaneCost pc = sweep_cost(capture, m, u, nsr, window);
    ExactPsfOptions eo;
    eo.object_distance_m = u;
    eo.rows = r;
    eo.cols = c;
    Plane h = exact_psf(m, eo);
    h /= h.sum();
    // residual(i, j) = p(i, j) - sum_{a, b} h(a, b) x(i - (a - r/2), j - (b - c/2)), cyclic.
    Plane res(r, c);
    for (int i = 0; i < r; ++i) {
        for (int j = 0; j < c; ++j) {
            double s = 0;
            for (int a = 0; a < r; ++a)
                for (int b = 0; b < c; ++b)
                    s += h(a, b) * pc.estimate(((i - (a - r / 2)) % r + r) % r,
                                               ((j - (b - c / 2)) % c + c) % c);
            res(i, j) = capture(i, j) - s;
        }
    }
    // The Wiener estimate leaves a residual (nsr > 0) that is not negligible here.
    CHECK(res.square().mean() > 1e-4);
    for (int i = 0; i < r; ++i) {
        for (int j = 0; j < c; ++j) {
            double s = 0;
            for (int a = -2; a <= 2; ++a)
                for (int b = -2; b <= 2; ++b) {
                    const double v = res(((i + a) % r + r) % r, ((j + b) % c + c) % c);
                    s += v * v;
                }
            CHECK(pc.cost(i, j) == doctest::Approx(s / 25.0).epsilon(1e-9));
        }
    }
}

TEST_CASE("sweep_cost refuses an even window, a window beyond the capture and a bad NSR") {
    const Mask m = small_mask();
    const Plane capture = Plane::Ones(16, 16);
    CHECK_THROWS_AS(sweep_cost(capture, m, 0.8, 0.05, 4), InvalidInput);
    CHECK_THROWS_AS(sweep_cost(capture, m, 0.8, 0.05, 17), InvalidInput);
    CHECK_THROWS_AS(sweep_cost(capture, m, 0.8, 0.0, 5), InvalidInput);
    CHECK_THROWS_AS(sweep_cost(capture, m, 0.01, 0.05, 5), InvalidInput);  // inside f'
}
