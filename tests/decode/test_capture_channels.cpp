// decode_channels: every channel decoded independently (threads for RGB), in channel order.
#include <doctest/doctest.h>

#include <limits>
#include <random>

#include "core/errors/error.hpp"
#include "decode/capture/capture.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;

using pinmask::test::random_plane;

TEST_CASE("RGB channels decoded on threads equal one decode_plane call per channel") {
    Image cap(17, 20, 3);
    for (int ch = 0; ch < 3; ++ch) cap.channels[ch] = random_plane(17, 20, 1 + ch);
    const Plane shared_psf = random_plane(5, 4, 9);
    DecodeOptions o;
    o.wiener.nsr = 0.05;
    // Deterministic FFTW plans: threaded and serial runs give identical numbers.
    const auto shared = decode_channels(cap, {shared_psf}, o);
    REQUIRE(shared.size() == 3);
    for (int ch = 0; ch < 3; ++ch)
        CHECK((shared[ch].image == decode_plane(cap.channels[ch], shared_psf, o).image).all());

    const std::vector<Plane> psfs = {random_plane(5, 4, 11), random_plane(3, 3, 12),
                                     random_plane(7, 2, 13)};
    const auto own = decode_channels(cap, psfs, o);
    for (int ch = 0; ch < 3; ++ch)
        CHECK((own[ch].image == decode_plane(cap.channels[ch], psfs[ch], o).image).all());
}

TEST_CASE("a mono capture decodes its one channel; errors of a channel propagate") {
    const Image mono(random_plane(12, 9, 3));
    DecodeOptions o;
    const auto one = decode_channels(mono, {random_plane(3, 3, 4)}, o);
    REQUIRE(one.size() == 1);
    CHECK(one[0].image.rows() == 12);
    CHECK(one[0].image.cols() == 9);

    Image cap(12, 9, 3);
    for (int ch = 0; ch < 3; ++ch) cap.channels[ch] = random_plane(12, 9, 5 + ch);
    cap.channels[1](2, 2) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(decode_channels(cap, {random_plane(3, 3, 4)}, o), InvalidInput);
    // Two PSFs for three channels: neither shared nor one per channel.
    CHECK_THROWS_AS(decode_channels(Image(12, 9, 3), {Plane::Ones(3, 3), Plane::Ones(3, 3)}, o),
                    InvalidInput);
}
