// Period estimation from the autocorrelation, and the check against the PSF size.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/errors/error.hpp"
#include "decode/capture/period.hpp"
#include "tests/support/close.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::random_plane;

namespace {

// FFT round-off relative to the zero-lag sum, amplified at large lags by the division by the
// overlap count (up to the side length, a few hundred here).
constexpr double kProfileVsDirectTol = 1e-10;
// A parabola through three samples of a peak whose true top lies between samples: its bias is a
// fraction of the sample spacing for the triangular-ish peaks of sums of cosines.
constexpr double kSubPixelTol = 0.25;

// rho(d) by the definition in period.hpp: direct sums over the overlapping pairs, normalised by
// the energies of the two overlapping parts.
std::vector<double> direct_profile(const Plane& x0, Axis axis) {
    const Plane x = x0 - x0.mean();
    const int R = static_cast<int>(x.rows()), C = static_cast<int>(x.cols());
    const int size = axis == Axis::kRows ? R : C;
    std::vector<double> rho(static_cast<std::size_t>(size));
    for (int d = 0; d < size; ++d) {
        double s = 0.0, head = 0.0, tail = 0.0;
        for (int r = 0; r < R; ++r)
            for (int c = 0; c < C; ++c) {
                const int r2 = axis == Axis::kRows ? r + d : r,
                          c2 = axis == Axis::kCols ? c + d : c;
                if (r2 >= R || c2 >= C) continue;
                s += x(r, c) * x(r2, c2);
                head += x(r, c) * x(r, c);
                tail += x(r2, c2) * x(r2, c2);
            }
        rho[static_cast<std::size_t>(d)] =
            head > 0.0 && tail > 0.0 ? s / std::sqrt(head * tail) : 0.0;
    }
    return rho;
}

// `tile` repeated over a rows x cols frame starting at phase (r0, c0) inside the tile.
Plane tiled(const Plane& tile, int rows, int cols, int r0, int c0) {
    Plane out(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            out(r, c) = tile((r + r0) % tile.rows(), (c + c0) % tile.cols());
    return out;
}

// Circular convolution of scene and psf (same size), by the direct O(N^2) sum.
Plane circular_convolution(const Plane& scene, const Plane& psf) {
    const int R = static_cast<int>(scene.rows()), C = static_cast<int>(scene.cols());
    Plane out = Plane::Zero(R, C);
    for (int r = 0; r < R; ++r)
        for (int c = 0; c < C; ++c)
            for (int i = 0; i < R; ++i)
                for (int j = 0; j < C; ++j)
                    out(r, c) += scene(i, j) * psf(((r - i) % R + R) % R, ((c - j) % C + C) % C);
    return out;
}

}  // namespace

TEST_CASE("autocorrelation_profile matches the direct sum (odd, prime, power-of-two sizes)") {
    for (const auto& size : {std::pair{16, 32}, std::pair{13, 17}, std::pair{9, 1}, std::pair{1, 7},
                             std::pair{31, 24}}) {
        const Plane x = random_plane(size.first, size.second, 7u * size.first + size.second);
        for (Axis axis : {Axis::kRows, Axis::kCols}) {
            const auto fast = autocorrelation_profile(x, axis);
            const auto ref = direct_profile(x, axis);
            REQUIRE(fast.size() == ref.size());
            INFO("size " << size.first << " x " << size.second);
            for (std::size_t d = 0; d < ref.size(); ++d)
                CHECK(std::fabs(fast[d] - ref[d]) <=
                      kProfileVsDirectTol * std::max(1.0, std::fabs(ref[d])));
            // Stopped at a lag (less padding, no wrap-around up to it): the same values.
            const int last = static_cast<int>(ref.size()) / 2;
            const auto part = autocorrelation_profile(x, axis, last);
            REQUIRE(part.size() == static_cast<std::size_t>(last + 1));
            for (int d = 0; d <= last; ++d)
                CHECK(std::fabs(part[std::size_t(d)] - ref[std::size_t(d)]) <=
                      kProfileVsDirectTol * std::max(1.0, std::fabs(ref[std::size_t(d)])));
        }
    }
    const auto flat = autocorrelation_profile(Plane::Constant(8, 8, 3.0), Axis::kRows);
    CHECK(flat[0] == 1.0);
    CHECK(flat[5] == 0.0);
}

TEST_CASE("strongest_repeat picks the first repeat, not its multiples or the central lobe") {
    // A central lobe decaying to 0.1, a repeat at 10 (0.8), a slightly larger one at 20 (0.85).
    std::vector<double> p(40, 0.1);
    for (int d = 0; d < 4; ++d) p[d] = 1.0 - 0.3 * d;
    p[9] = 0.5;
    p[10] = 0.8;
    p[11] = 0.5;
    p[19] = 0.5;
    p[20] = 0.85;
    p[21] = 0.5;
    const auto pk = strongest_repeat(p, 30, 0.1);
    REQUIRE(pk.has_value());
    CHECK(pk->lag == doctest::Approx(10.0));
    CHECK(pk->rise == doctest::Approx(0.7));
    // Out of the search range, or too small a rise: no repeat.
    CHECK_FALSE(strongest_repeat(p, 8, 0.1).has_value());
    CHECK_FALSE(strongest_repeat(p, 30, 0.9).has_value());
    // An asymmetric peak moves the parabola's vertex towards the larger neighbour.
    p[11] = 0.7;
    const auto pk2 = strongest_repeat(p, 15, 0.1);
    REQUIRE(pk2.has_value());
    CHECK(pk2->lag > 10.0);
    CHECK(pk2->lag < 10.5);
}

TEST_CASE("check_period finds the period of a tiled coded capture with noise") {
    // One period: a sparse pinhole-like PSF (4 x 4 pixel spots) convolved with a smooth scene;
    // the sensor sees that period repeated, starting at an arbitrary phase, plus noise.
    const int P = 32;
    Plane psf = Plane::Zero(P, P);
    const int holes[][2] = {{0, 0}, {3, 5}, {1, 6}, {6, 2}, {5, 7}, {7, 4}};
    for (const auto& h : holes) psf.block(4 * h[0], 4 * h[1], 4, 4) = 1.0;
    Plane scene(P, P);
    for (int r = 0; r < P; ++r)
        for (int c = 0; c < P; ++c)
            scene(r, c) = 1.0 + std::sin(2 * std::numbers::pi * r / P) *
                                    std::cos(2 * std::numbers::pi * c / P);
    const Plane period = circular_convolution(scene, psf);
    Plane capture = tiled(period, 101, 150, 7, 19);
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, 0.05 * period.mean());
    for (Eigen::Index i = 0; i < capture.size(); ++i) capture.data()[i] += noise(rng);

    const PeriodCheck ok = check_period(capture, P, P);
    CHECK(ok.checked());
    CHECK(ok.rows.checked);
    CHECK(ok.cols.checked);
    CHECK(ok.rows.found);
    CHECK(ok.cols.found);
    CHECK(std::fabs(ok.rows.measured_px - P) <= kSubPixelTol);
    CHECK(std::fabs(ok.cols.measured_px - P) <= kSubPixelTol);
    CHECK(ok.matches());

    // The same capture checked against a PSF of another size: a mismatch with the true figure.
    const PeriodCheck bad = check_period(capture, 28, 36);
    CHECK_FALSE(bad.matches());
    CHECK(std::fabs(bad.rows.measured_px - P) <= kSubPixelTol);
    CHECK(std::fabs(bad.cols.measured_px - P) <= kSubPixelTol);
}

TEST_CASE("check_period measures a non-integer period to sub-pixel accuracy") {
    // Rows repeat every 21.4 px, columns every 16 px (cosine sums with harmonics: sharp peaks).
    const double pr = 21.4, pc = 16.0;
    Plane x(128, 96);
    for (int r = 0; r < x.rows(); ++r)
        for (int c = 0; c < x.cols(); ++c) {
            double v = 0.0;
            for (int k = 1; k <= 4; ++k)
                v += std::cos(2 * std::numbers::pi * k * r / pr) +
                     std::cos(2 * std::numbers::pi * k * c / pc + k);
            x(r, c) = v;
        }
    const PeriodCheck check = check_period(x, 21, 16);
    REQUIRE(check.rows.found);
    REQUIRE(check.cols.found);
    CHECK(std::fabs(check.rows.measured_px - pr) <= kSubPixelTol);
    CHECK(std::fabs(check.cols.measured_px - pc) <= kSubPixelTol);
    CHECK(check.cols.matches);
    CHECK(check.rows.matches);  // 21.4 rounds to 21: within half a pixel
    const PeriodCheck far = check_period(x, 20, 16);
    CHECK_FALSE(far.rows.matches);  // 21.4 vs 20
    CHECK_FALSE(far.matches());
}

TEST_CASE("check_period skips an axis with fewer than two periods, and finds none in noise") {
    const Plane x = random_plane(60, 100, 3);
    const PeriodCheck one = check_period(x, 31, 40);
    CHECK_FALSE(one.rows.checked);  // 60 < 2 * 31
    CHECK(one.rows.skip_reason.find("1.94 periods") != std::string::npos);
    CHECK_FALSE(one.cols.checked);  // white noise does not repeat: nothing to check
    CHECK_FALSE(one.cols.found);
    CHECK(one.cols.skip_reason.find("no repeat found") != std::string::npos);
    CHECK(one.matches());  // no repeat contradicts the PSF either

    const PeriodCheck none = check_period(x, 60, 100);
    CHECK_FALSE(none.checked());
    CHECK(none.matches());  // nothing checked, nothing contradicted

    CHECK_THROWS_AS(check_period(x, 0, 10), InvalidInput);
    CHECK_THROWS_AS(check_period(Plane(0, 0), 1, 1), InvalidInput);
}

TEST_CASE("check_period on an image equals the check of its luminance plane (strips read)") {
    // A frame wide and tall enough for strips (> kAcrossStrips * kStripWidth lines across), three
    // channels with a common 40 x 36 repeat and different weights.
    const Plane tile = random_plane(40, 36, 21);
    Image img;
    for (double w : {1.0, 0.5, 2.0}) img.channels.push_back(w * tiled(tile, 300, 410, 3, 11));
    Plane sum = img.channels[0] + img.channels[1] + img.channels[2];
    const PeriodCheck a = check_period(img, 40, 36);
    const PeriodCheck b = check_period(sum, 40, 36);
    REQUIRE(a.rows.found);
    REQUIRE(a.cols.found);
    CHECK(a.rows.measured_px == b.rows.measured_px);
    CHECK(a.cols.measured_px == b.cols.measured_px);
    CHECK(a.rows.peak_rise == b.rows.peak_rise);
    CHECK(std::fabs(a.rows.measured_px - 40) <= kSubPixelTol);
    CHECK(std::fabs(a.cols.measured_px - 36) <= kSubPixelTol);
    CHECK(a.matches());
    // A NaN in a line the check reads is an error (never a silent verdict).
    sum(150, 410 / (2 * kAcrossStrips)) = std::nan("");
    CHECK_THROWS_AS(check_period(sum, 40, 36), InvalidInput);
}

TEST_CASE("check_period on hostile frames: no crash, a sensible answer") {
    // Constant and all-zero frames: nothing repeats measurably, both axes skipped, no warning.
    for (double v : {0.0, 7.5}) {
        const PeriodCheck flat = check_period(Plane::Constant(300, 400, v), 40, 50);
        CHECK_FALSE(flat.checked());
        CHECK(flat.matches());
        CHECK(flat.rows.skip_reason.find("no repeat found") != std::string::npos);
    }
    // Noise only (no repeat): skipped, whatever period is asked, early exit never taken.
    const Plane noise = random_plane(500, 600, 17);
    for (int p : {3, 40, 128, 250}) {
        const PeriodCheck n = check_period(noise, p, p);
        CHECK_FALSE(n.rows.early_exit);
        CHECK_FALSE(n.cols.early_exit);
        CHECK_FALSE(n.rows.found);
        CHECK_FALSE(n.cols.found);
        CHECK(n.matches());
    }
    // One row, one column, 1 x 1, 2 x 2: the short axis holds fewer than two periods (skipped),
    // the long one is checked as any other.
    const Plane tile = random_plane(1, 16, 5);
    Plane row(1, 160);
    for (int c = 0; c < 160; ++c) row(0, c) = tile(0, c % 16);
    const PeriodCheck r = check_period(row, 1, 16);
    CHECK(r.rows.checked == false);
    REQUIRE(r.cols.found);
    CHECK(std::fabs(r.cols.measured_px - 16) <= kSubPixelTol);
    CHECK(r.matches());
    CHECK_FALSE(check_period(row, 1, 20).matches());
    const PeriodCheck col = check_period(Plane(row.transpose()), 16, 1);
    REQUIRE(col.rows.found);
    CHECK(std::fabs(col.rows.measured_px - 16) <= kSubPixelTol);
    for (int side : {1, 2, 3}) {
        const PeriodCheck tiny = check_period(random_plane(side, side, 9), 1, 1);
        CHECK(tiny.matches());  // lags 2 .. size - 2 do not exist: nothing found, nothing wrong
    }
    // Period 1 and 2 (the early exit needs lags below P - w: the full search decides).
    const PeriodCheck p2 = check_period(tiled(random_plane(2, 2, 3), 64, 64, 0, 0), 2, 2);
    CHECK(p2.matches());
    // A NaN anywhere in the frame read by the full search is an error, never a verdict.
    Plane nan = noise;
    nan(250, 3) = std::nan("");
    CHECK_THROWS_AS(check_period(nan, 40, 50), InvalidInput);
}

TEST_CASE("check_period's early exit agrees with the full search on a clean tiled capture") {
    // A sharp random tile repeated: the early exit takes it; the profile of every lag (the full
    // search's input) peaks at the same lag to within the parabola's bias.
    const Plane tile = random_plane(37, 45, 23);
    Plane x = tiled(tile, 400, 420, 5, 9);
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 0.1);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] += noise(rng);
    const PeriodCheck check = check_period(x, 37, 45);
    CHECK(check.rows.early_exit);
    CHECK(check.cols.early_exit);
    CHECK(check.matches());
    const auto rows = autocorrelation_profile(x, Axis::kRows, 300);
    const auto full = strongest_repeat(rows, 260, 0.1);
    REQUIRE(full.has_value());
    CHECK(std::fabs(full->lag - check.rows.measured_px) <= kSubPixelTol);
    // The same capture against a PSF one pixel off the tolerance (37 +- 2): the search reports 37.
    for (int e : {35, 39}) {
        const PeriodCheck off = check_period(x, e, 45);
        CHECK_FALSE(off.rows.early_exit);
        CHECK_FALSE(off.rows.matches);
        CHECK(std::fabs(off.rows.measured_px - 37) <= kSubPixelTol);
    }
    // Repeating at half the PSF's period (74 = 2 x 37): reported as 37, not accepted at 74.
    const PeriodCheck half = check_period(x, 74, 45);
    CHECK_FALSE(half.rows.early_exit);
    CHECK_FALSE(half.rows.matches);
    CHECK(std::fabs(half.rows.measured_px - 37) <= kSubPixelTol);
}
