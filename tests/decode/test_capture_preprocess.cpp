// DiffuserCam-style preprocessing: corner background, 2x2 box downsampling, L2 normalisation.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/errors/error.hpp"
#include "decode/capture/preprocess.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::random_plane;

namespace {

// Sums of a few hundred doubles of order 1: round-off is a few ulps times the count.
constexpr double kSumRoundoffTol = 1e-13;

}  // namespace

TEST_CASE("corner_background is the mean of rows and cols 5..14") {
    const Plane p = random_plane(20, 23, 1, -1.0, 2.0);
    double sum = 0.0;
    for (int r = 5; r <= 14; ++r)
        for (int c = 5; c <= 14; ++c) sum += p(r, c);
    CHECK_CLOSE(corner_background(p), sum / 100.0, kSumRoundoffTol);
    // The patch needs 15 x 15 pixels.
    CHECK_NOTHROW(corner_background(random_plane(15, 15, 2, -1.0, 2.0)));
    CHECK_THROWS_AS(corner_background(random_plane(14, 40, 2, -1.0, 2.0)), InvalidInput);
    CHECK_THROWS_AS(patch_mean(p, -1, 0, 3), InvalidInput);
}

TEST_CASE("box_downsample_2x averages 2x2 blocks and drops an odd last row/column") {
    for (const auto& size :
         {std::pair{8, 8}, std::pair{7, 11}, std::pair{13, 2}, std::pair{2, 3}}) {
        const Plane p = random_plane(size.first, size.second, 3, -1.0, 2.0);
        const Plane d = box_downsample_2x(p);
        INFO("size " << size.first << " x " << size.second);
        REQUIRE(d.rows() == size.first / 2);
        REQUIRE(d.cols() == size.second / 2);
        for (int r = 0; r < d.rows(); ++r)
            for (int c = 0; c < d.cols(); ++c) {
                const double ref = (p(2 * r, 2 * c) + p(2 * r + 1, 2 * c) + p(2 * r, 2 * c + 1) +
                                    p(2 * r + 1, 2 * c + 1)) /
                                   4.0;
                CHECK_CLOSE(d(r, c), ref, kSumRoundoffTol);
            }
    }
    CHECK_THROWS_AS(box_downsample_2x(random_plane(1, 5, 4, -1.0, 2.0)), InvalidInput);
}

TEST_CASE("box_downsample by k rounds equals a 2^k block mean") {
    const Plane p = random_plane(48, 40, 5, -1.0, 2.0);
    const Plane d = box_downsample(p, 3);
    REQUIRE(d.rows() == 6);
    REQUIRE(d.cols() == 5);
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 5; ++c)
            CHECK_CLOSE(d(r, c), p.block(8 * r, 8 * c, 8, 8).mean(), kSumRoundoffTol);
    CHECK((box_downsample(p, 0) == p).all());
    CHECK_THROWS_AS(box_downsample(p, -1), InvalidInput);
    CHECK_THROWS_AS(box_downsample(p, 6), InvalidInput);  // 48 -> 0 rows after 6 rounds
}

TEST_CASE("one normalisation factor over the channels, counted by hand") {
    // Mono: the image's own L2 norm and sum.
    const Plane p = random_plane(9, 17, 6, -1.0, 2.0);
    double sq = 0.0, sum = 0.0;
    for (Eigen::Index i = 0; i < p.size(); ++i) {
        sq += p.data()[i] * p.data()[i];
        sum += p.data()[i];
    }
    CHECK_CLOSE(channels_l2_norm({p}, "capture"), std::sqrt(sq), kSumRoundoffTol);
    // Channels of 3 x 4 constants 1, 2, 4: norms sqrt(12) x {1, 2, 4}, sums 12 x {1, 2, 4}; the
    // root mean square of the norms is sqrt(12 x 21 / 3), the mean sum 12 x 7 / 3.
    const std::vector<Plane> rgb{Plane::Constant(3, 4, 1.0), Plane::Constant(3, 4, 2.0),
                                 Plane::Constant(3, 4, 4.0)};
    CHECK_CLOSE(channels_l2_norm(rgb, "PSF"), std::sqrt(84.0), kSumRoundoffTol);
    CHECK_CLOSE(channels_mean_sum(rgb, "PSF"), 28.0, kSumRoundoffTol);
    CHECK_CLOSE(channels_mean_sum({p}, "PSF"), sum, kSumRoundoffTol);
    CHECK_THROWS_AS(channels_l2_norm({Plane::Zero(3, 3)}, "capture"), InvalidInput);
    CHECK_THROWS_AS(channels_mean_sum({Plane::Constant(3, 3, -1.0)}, "PSF"), InvalidInput);
}
