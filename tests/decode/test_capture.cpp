// Capture pipeline steps that do not decode: validation, dark frame, crop window and crop.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/errors/error.hpp"
#include "decode/capture/capture.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;

using pinmask::test::random_plane;

TEST_CASE("check_image_finite names the first bad pixel") {
    Image img(random_plane(5, 7, 1));
    CHECK_NOTHROW(check_image_finite(img, "capture"));
    img.channels[0](3, 4) = std::numeric_limits<double>::quiet_NaN();
    try {
        check_image_finite(img, "capture");
        FAIL("expected InvalidInput");
    } catch (const InvalidInput& e) {
        const std::string msg = e.what();
        CHECK(msg.find("row 3, col 4") != std::string::npos);
        CHECK(msg.find("NaN") != std::string::npos);
    }
    img.channels[0](3, 4) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(check_image_finite(img, "capture"), InvalidInput);
    CHECK_THROWS_AS(check_image_finite(Image{}, "capture"), InvalidInput);
}

TEST_CASE("check_psf refuses zero, negative-sum and non-finite PSFs") {
    CHECK_NOTHROW(check_psf(random_plane(4, 4, 2), "psf"));
    CHECK_THROWS_AS(check_psf(Plane::Zero(4, 4), "psf"), InvalidInput);
    Plane neg = -random_plane(4, 4, 3);
    CHECK_THROWS_AS(check_psf(neg, "psf"), InvalidInput);
    Plane inf = random_plane(4, 4, 4);
    inf(1, 1) = -std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(check_psf(inf, "psf"), InvalidInput);
}

TEST_CASE("subtract_dark: per channel, a mono dark applies to every channel") {
    Image cap(6, 9, 3);
    for (int ch = 0; ch < 3; ++ch) cap.channels[ch] = random_plane(6, 9, 10 + ch);
    const Image dark_mono(random_plane(6, 9, 20));
    const Image out = subtract_dark(cap, dark_mono);
    REQUIRE(out.n_channels() == 3);
    for (int ch = 0; ch < 3; ++ch)
        for (int r = 0; r < 6; ++r)
            for (int c = 0; c < 9; ++c)
                CHECK(out.channels[ch](r, c) ==
                      cap.channels[ch](r, c) - dark_mono.channels[0](r, c));

    Image dark_rgb(6, 9, 3);
    for (int ch = 0; ch < 3; ++ch) dark_rgb.channels[ch] = random_plane(6, 9, 30 + ch);
    const Image out3 = subtract_dark(cap, dark_rgb);
    CHECK(out3.channels[2](5, 8) == cap.channels[2](5, 8) - dark_rgb.channels[2](5, 8));
}

TEST_CASE("subtract_dark refuses another size or channel count") {
    const Image cap(random_plane(6, 9, 1));
    CHECK_THROWS_AS(subtract_dark(cap, Image(random_plane(9, 6, 2))), InvalidInput);
    CHECK_THROWS_AS(subtract_dark(cap, Image(random_plane(6, 8, 2))), InvalidInput);
    CHECK_THROWS_AS(subtract_dark(Image(6, 9, 3), Image(6, 9, 2)), InvalidInput);
}

TEST_CASE("crop_window: centre follows floor((R - P) / 2) for odd, prime and even sizes") {
    const int frames[][2] = {{128, 128}, {131, 257}, {480, 720}, {17, 19}, {7, 7}};
    const int periods[][2] = {{128, 128}, {31, 64}, {13, 13}, {7, 2}, {1, 1}};
    for (const auto& f : frames)
        for (const auto& p : periods) {
            if (p[0] > f[0] || p[1] > f[1]) continue;
            const CropWindow w = crop_window(f[0], f[1], p[0], p[1], {});
            INFO("frame " << f[0] << "x" << f[1] << " period " << p[0] << "x" << p[1]);
            CHECK(w.rows == p[0]);
            CHECK(w.cols == p[1]);
            CHECK(w.row == (f[0] - p[0]) / 2);
            CHECK(w.col == (f[1] - p[1]) / 2);
            // The window's centre is the frame's centre to within half a pixel per axis.
            CHECK(std::fabs((w.row + w.rows / 2.0) - f[0] / 2.0) <= 0.5);
            CHECK(std::fabs((w.col + w.cols / 2.0) - f[1] / 2.0) <= 0.5);
        }
}

TEST_CASE("crop_window: none is the whole frame, corner is checked against the frame") {
    const CropWindow all = crop_window(40, 50, 64, 64, {CropMode::kNone});
    CHECK(all.row == 0);
    CHECK(all.col == 0);
    CHECK(all.rows == 40);
    CHECK(all.cols == 50);

    const CropWindow w = crop_window(40, 50, 16, 20, {CropMode::kCorner, 24, 30});
    CHECK(w.row == 24);
    CHECK(w.col == 30);
    CHECK_THROWS_AS(crop_window(40, 50, 16, 20, {CropMode::kCorner, 25, 30}), InvalidInput);
    CHECK_THROWS_AS(crop_window(40, 50, 16, 20, {CropMode::kCorner, 0, 31}), InvalidInput);
    CHECK_THROWS_AS(crop_window(40, 50, 16, 20, {CropMode::kCorner, -1, 0}), InvalidInput);
    // A frame smaller than one period cannot be cropped to a period.
    CHECK_THROWS_AS(crop_window(40, 50, 41, 20, {}), InvalidInput);
    CHECK_THROWS_AS(crop_window(40, 50, 16, 51, {CropMode::kCorner, 0, 0}), InvalidInput);
}

TEST_CASE("crop copies the window's pixels of every channel") {
    Image img(11, 13, 3);
    for (int ch = 0; ch < 3; ++ch) img.channels[ch] = random_plane(11, 13, 40 + ch);
    const CropWindow w{3, 5, 4, 7};
    const Image out = crop(img, w);
    REQUIRE(out.n_channels() == 3);
    CHECK(out.rows() == 4);
    CHECK(out.cols() == 7);
    for (int ch = 0; ch < 3; ++ch)
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 7; ++c)
                CHECK(out.channels[ch](r, c) == img.channels[ch](3 + r, 5 + c));
}
