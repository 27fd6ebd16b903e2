#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/image/image_io.hpp"
#include "optimize/simulate/scenes.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::random_plane;

namespace {

// Sums of a few thousand doubles in a different order: round-off only.
constexpr double kRoundoffTol = 1e-12;

// Reference resampler: replicate every input pixel into an (rows x cols) block, which puts both
// grids on one common fine grid, then average blocks of (H x W). Exact for any sizes.
Plane resample_reference(const Plane& in, int rows, int cols) {
    const int H = static_cast<int>(in.rows()), W = static_cast<int>(in.cols());
    Plane out = Plane::Zero(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            double s = 0.0;
            for (int fr = r * H; fr < (r + 1) * H; ++fr)
                for (int fc = c * W; fc < (c + 1) * W; ++fc) s += in(fr / rows, fc / cols);
            out(r, c) = s / (static_cast<double>(H) * W);
        }
    return out;
}

}  // namespace

TEST_CASE("every built-in scene: requested size, values in [0, 1], deterministic") {
    const int sizes[][2] = {{1, 1}, {17, 23}, {64, 64}, {31, 128}};
    for (const auto& name : builtin_scene_names()) {
        for (const auto& s : sizes) {
            INFO(name << " " << s[0] << " x " << s[1]);
            const SceneSpec spec = scene_from_name(name);
            const Image a = make_scene(spec, s[0], s[1]);
            const Image b = make_scene(spec, s[0], s[1]);
            REQUIRE(a.n_channels() == 1);
            CHECK(a.rows() == s[0]);
            CHECK(a.cols() == s[1]);
            CHECK(a.channels[0].minCoeff() >= 0.0);
            CHECK(a.channels[0].maxCoeff() <= 1.0);
            CHECK((a.channels[0] == b.channels[0]).all());
        }
        CHECK(scene_name(scene_from_name(name)) == name);
    }
    CHECK_THROWS_AS(make_scene(scene_from_name("usaf"), 0, 5), InvalidInput);
}

TEST_CASE("unknown scene names are rejected with the list of built-ins") {
    CHECK_THROWS_WITH_AS(scene_from_name("no-such-scene.png"), doctest::Contains("siemens-star"),
                         InvalidInput);
}

TEST_CASE("point scene: a single 1 at the centre pixel") {
    for (auto [r, c] : {std::pair{7, 7}, std::pair{8, 5}, std::pair{1, 1}}) {
        const Plane p = point_scene(r, c);
        CHECK(p.sum() == 1.0);
        CHECK(p(r / 2, c / 2) == 1.0);
    }
}

TEST_CASE("checker: exact parity at integer square sizes, exact area averages otherwise") {
    const Plane p = checker_scene(64, 48, 6);  // squares of 8 pixels
    for (int r = 0; r < 64; ++r)
        for (int c = 0; c < 48; ++c) CHECK(p(r, c) == ((r / 8 + c / 8) % 2 == 0 ? 1.0 : 0.0));
    // 20 / 8 = 2.5-pixel squares: twice the resolution has 5-pixel squares (exact), and area
    // averaging that down must give the same picture.
    const Plane fine = checker_scene(40, 40, 8);
    CHECK((checker_scene(20, 20, 8) - resample_reference(fine, 20, 20)).abs().maxCoeff() <=
          kRoundoffTol);
}

TEST_CASE("USAF target: exact coverage, so rendering twice as fine and averaging agrees") {
    for (const auto& size : {std::pair{64, 64}, std::pair{45, 77}}) {
        const int r = size.first, c = size.second;
        const Plane coarse = usaf_scene(r, c);
        const Plane fine = usaf_scene(2 * r, 2 * c);
        INFO(r << " x " << c);
        CHECK((coarse - resample_reference(fine, r, c)).abs().maxCoeff() <= kRoundoffTol);
        CHECK(coarse.mean() > 0.05);
        CHECK(coarse.mean() < 0.5);
    }
    // The first element's vertical bars: three runs of ink along a row through them.
    const Plane p = usaf_scene(200, 200);
    const int row = static_cast<int>(0.04 * 200 + 0.15 * 200);  // mid-height of element 0
    int runs = 0;
    for (int c = 1; c < static_cast<int>(0.04 * 200 + 0.06 * 5 * 200); ++c)
        runs += (p(row, c) > 0.5 && p(row, c - 1) <= 0.5);
    CHECK(runs == 3);
}

TEST_CASE("Siemens star: the uniform-pixel shortcut equals full supersampling") {
    const int rows = 37, cols = 41, spokes = 12, m = kStarSupersample;
    const Plane p = siemens_star_scene(rows, cols, spokes);
    const double radius = 0.45 * std::min(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            int hits = 0;
            for (int i = 0; i < m; ++i)
                for (int j = 0; j < m; ++j) {
                    const double y = r + (i + 0.5) / m - rows / 2.0;
                    const double x = c + (j + 0.5) / m - cols / 2.0;
                    hits += x * x + y * y <= radius * radius &&
                            std::sin(spokes * std::atan2(y, x)) > 0.0;
                }
            CHECK(p(r, c) == static_cast<double>(hits) / (m * m));
        }
    // Half the disk is bright. Tolerance: the rim is sampled on an 8 x 8 grid per pixel.
    constexpr double kStarAreaTol = 0.02;
    const Plane big = siemens_star_scene(256, 256, 16);
    CHECK_CLOSE(big.sum(), std::numbers::pi * std::pow(0.45 * 256, 2) / 2.0, kStarAreaTol);
}

TEST_CASE("letter R: ink box fills the frame inside the margin") {
    const int rows = 120, cols = 90;
    const Plane p = letter_r_scene(rows, cols);
    int top = rows, bottom = -1, left = cols, right = -1;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            if (p(r, c) > 0.0) {
                top = std::min(top, r);
                bottom = std::max(bottom, r);
                left = std::min(left, c);
                right = std::max(right, c);
            }
    // The ink box edges fall inside the margin pixel (anti-aliased coverage), +- 1 pixel.
    CHECK(std::abs(top - static_cast<int>(kLetterMargin * rows)) <= 1);
    CHECK(std::abs(bottom - static_cast<int>((1 - kLetterMargin) * rows)) <= 1);
    CHECK(std::abs(left - static_cast<int>(kLetterMargin * cols)) <= 1);
    CHECK(std::abs(right - static_cast<int>((1 - kLetterMargin) * cols)) <= 1);
    CHECK(p.mean() > 0.25);  // a bold letter covers a good part of its box
    CHECK(p.mean() < 0.7);
    // Not mirror-symmetric (an R, not an H or an O).
    CHECK((p - p.rowwise().reverse()).abs().mean() > 0.1);
}

TEST_CASE("natural scene: seeded, spans [0, 1], radial power falls like 1/f^(2 alpha)") {
    const int n = 64;
    const Plane a = natural_scene(n, n, 3, 1.0);
    CHECK(a.minCoeff() == 0.0);
    CHECK(a.maxCoeff() == 1.0);
    CHECK((a == natural_scene(n, n, 3, 1.0)).all());
    CHECK(!(a == natural_scene(n, n, 4, 1.0)).all());
    // Least-squares slope of log power against log f over 4 <= |f| n <= 24 (rings averaged over
    // 8 seeds; the affine [0,1] mapping scales power but not its slope).
    for (double alpha : {1.0, 1.5}) {
        const Fft2 fft(n, n);
        std::vector<double> ring(n, 0.0);
        std::vector<int> count(n, 0);
        for (std::uint64_t seed = 0; seed < 8; ++seed) {
            const ComplexPlane s = fft.forward(natural_scene(n, n, seed, alpha));
            for (int k = 0; k < n; ++k)
                for (int l = 0; l < fft.half_cols(); ++l) {
                    const int f = static_cast<int>(std::lround(std::hypot(std::min(k, n - k), l)));
                    if (f < n) {
                        ring[f] += std::norm(s(k, l));
                        ++count[f];
                    }
                }
        }
        double sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;
        for (int f = 4; f <= 24; ++f) {
            const double x = std::log(f), y = std::log(ring[f] / count[f]);
            sx += x, sy += y, sxx += x * x, sxy += x * y, m += 1;
        }
        const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
        // Tolerance: ring averages of 8 seeds scatter by a few percent; the slope over a
        // factor 6 of frequency is good to about 0.15.
        constexpr double kSlopeTol = 0.15;
        INFO("alpha " << alpha << " slope " << slope);
        CHECK(std::fabs(slope + 2.0 * alpha) <= kSlopeTol);
    }
}

TEST_CASE("area resampling matches the common-fine-grid reference, any sizes") {
    const Plane in = random_plane(7, 11, 5);
    for (const auto& size : {std::pair{3, 4}, std::pair{7, 11}, std::pair{13, 5}, std::pair{1, 1},
                             std::pair{14, 22}}) {
        const int r = size.first, c = size.second;
        INFO(r << " x " << c);
        const Plane out = resample_area(in, r, c);
        CHECK((out - resample_reference(in, r, c)).abs().maxCoeff() <= kRoundoffTol);
        CHECK(std::fabs(out.mean() - in.mean()) <= kRoundoffTol);
    }
}

TEST_CASE("file scenes: normalised by full scale, resampled, RGB kept, bad values rejected") {
    test::TempDir dir("scenes");
    Image grey(random_plane(20, 30, 7));
    write_png(dir / "g.png", grey, 8);
    const LoadedImage loaded = read_image(dir / "g.png");
    const Plane expect = resample_area(loaded.image.channels[0] / 255.0, 10, 12);
    const Image got = make_scene(scene_from_name(dir / "g.png"), 10, 12);
    REQUIRE(got.n_channels() == 1);
    CHECK((got.channels[0] - expect).abs().maxCoeff() <= kRoundoffTol);

    Image rgb(20, 30, 3);
    for (int ch = 0; ch < 3; ++ch) rgb.channels[ch] = random_plane(20, 30, 10 + ch);
    write_png(dir / "c.png", rgb, 16);
    const Image got_rgb = file_scene(dir / "c.png", 9, 9);
    CHECK(got_rgb.n_channels() == 3);
    CHECK(got_rgb.channels[2].maxCoeff() <= 1.0);

    Image hot(Plane::Constant(4, 4, 1.5));
    write_tiff(dir / "hot.tif", hot, SampleFormat::kFloat32);
    CHECK_THROWS_WITH_AS(file_scene(dir / "hot.tif", 4, 4), doctest::Contains("[0, 1]"),
                         InvalidInput);
}
