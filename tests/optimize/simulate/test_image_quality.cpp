#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/errors/error.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::random_plane;

namespace {

// Separable filtering against a direct 121-term sum: round-off of sums of O(100) terms.
constexpr double kSsimVsDirectTol = 1e-12;

// SSIM of the 11 x 11 window whose top-left pixel is (r0, c0), straight from the paper's
// formulas with the 2-D weights exp(-(i^2 + j^2) / (2 sigma^2)) normalised over the window.
double direct_ssim_at(const Plane& x, const Plane& y, int r0, int c0) {
    double w[11][11], wsum = 0.0;
    for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
            w[i][j] = std::exp(-((i - 5.0) * (i - 5.0) + (j - 5.0) * (j - 5.0)) / (2 * 1.5 * 1.5));
            wsum += w[i][j];
        }
    double mx = 0, my = 0;
    for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
            mx += w[i][j] / wsum * x(r0 + i, c0 + j);
            my += w[i][j] / wsum * y(r0 + i, c0 + j);
        }
    double vx = 0, vy = 0, cxy = 0;
    for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
            const double dx = x(r0 + i, c0 + j) - mx, dy = y(r0 + i, c0 + j) - my;
            vx += w[i][j] / wsum * dx * dx;
            vy += w[i][j] / wsum * dy * dy;
            cxy += w[i][j] / wsum * dx * dy;
        }
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    return (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
}

}  // namespace

TEST_CASE("MSE and PSNR: closed forms") {
    const Plane ref = random_plane(9, 13, 1);
    const Plane x = ref + 0.1;
    CHECK_CLOSE(mse(x, ref), 0.01, 1e-12);
    CHECK_CLOSE(psnr_db(x, ref), 20.0, 1e-12);
    CHECK(std::isinf(psnr_db(ref, ref)));
    CHECK_THROWS_AS(mse(x, Plane::Zero(9, 12)), InvalidInput);
    CHECK_THROWS_AS(psnr_from_mse(-1.0), InvalidInput);
}

TEST_CASE("SSIM of identical images is 1") {
    for (auto [r, c] : {std::pair{11, 11}, std::pair{13, 17}, std::pair{32, 32}}) {
        const Plane a = random_plane(r, c, 2);
        CHECK(ssim_map(a, a).rows() == r - 10);
        CHECK(ssim_map(a, a).cols() == c - 10);
        CHECK(std::fabs(ssim(a, a) - 1.0) <= kSsimVsDirectTol);
    }
}

TEST_CASE("SSIM of constant images: (2 a b + C1) / (a^2 + b^2 + C1)") {
    const double a = 0.3, b = 0.7, c1 = 1e-4;
    const Plane x = Plane::Constant(16, 16, a), y = Plane::Constant(16, 16, b);
    CHECK_CLOSE(ssim(x, y), (2 * a * b + c1) / (a * a + b * b + c1), kSsimVsDirectTol);
}

TEST_CASE("SSIM map matches the direct per-window formulas (odd, prime, even sizes)") {
    for (auto [r, c] : {std::pair{11, 11}, std::pair{13, 17}, std::pair{24, 31}}) {
        const Plane x = random_plane(r, c, 3);
        const Plane y = (0.6 * x + 0.4 * random_plane(r, c, 4)).eval();
        const Plane map = ssim_map(x, y);
        double sum = 0.0;
        for (int i = 0; i < map.rows(); ++i)
            for (int j = 0; j < map.cols(); ++j) {
                const double d = direct_ssim_at(x, y, i, j);
                sum += d;
                CHECK(std::fabs(map(i, j) - d) <= kSsimVsDirectTol);
            }
        CHECK(std::fabs(ssim(x, y) - sum / map.size()) <= kSsimVsDirectTol);
        CHECK(std::fabs(ssim(x, y) - ssim(y, x)) <= kSsimVsDirectTol);  // symmetric
        CHECK(ssim(x, y) < 1.0);
    }
}

TEST_CASE("SSIM rejects images smaller than the window; multi-channel averages channels") {
    CHECK_THROWS_WITH_AS(ssim(Plane::Zero(10, 20), Plane::Zero(10, 20)), doctest::Contains("11"),
                         InvalidInput);
    Image a(16, 16, 2), b(16, 16, 2);
    a.channels[0] = random_plane(16, 16, 5);
    a.channels[1] = random_plane(16, 16, 6);
    b.channels[0] = a.channels[0];
    b.channels[1] = random_plane(16, 16, 7);
    CHECK_CLOSE(ssim(a, b), 0.5 * (1.0 + ssim(a.channels[1], b.channels[1])), kSsimVsDirectTol);
    CHECK_CLOSE(mse(a, b), 0.5 * mse(a.channels[1], b.channels[1]), kSsimVsDirectTol);
}
