#include <doctest/doctest.h>

#include "core/errors/error.hpp"
#include "decode/solvers/convolution.hpp"
#include "tests/decode/test_decode_support.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// <y, A x> and <A^T y, x> are sums of N products of O(1) terms evaluated along different FFT
// paths: rounding ~ 1e-16 * sqrt(N) * log N relative to the sum of |terms|, well under 1e-12.
constexpr double kAdjointTol = 1e-12;
// FFT convolution against the O(N * psf) direct sum.
constexpr double kConvVsDirectTol = 1e-12;

double dot(const Plane& a, const Plane& b) { return (a * b).sum(); }

// Direct linear convolution of the capture window: out(i, j) = sum psf(r, c) x(i + o_r - r + cr,
// j + o_c - c + cc); counts the indices outside the grid (wrap-around reaching the window).
Plane direct_linear(const Plane& psf, const Plane& x, const ConvGeometry& g, int& outside) {
    Plane out = Plane::Zero(g.capture_rows, g.capture_cols);
    const Eigen::Index cr = psf.rows() / 2, cc = psf.cols() / 2;
    for (int i = 0; i < g.capture_rows; ++i)
        for (int j = 0; j < g.capture_cols; ++j)
            for (Eigen::Index r = 0; r < psf.rows(); ++r)
                for (Eigen::Index c = 0; c < psf.cols(); ++c) {
                    const Eigen::Index xi = i + g.crop_row - (r - cr);
                    const Eigen::Index xj = j + g.crop_col - (c - cc);
                    if (xi < 0 || xi >= g.work_rows || xj < 0 || xj >= g.work_cols) {
                        ++outside;
                        continue;
                    }
                    out(i, j) += psf(r, c) * x(xi, xj);
                }
    return out;
}

}  // namespace

TEST_CASE("next_fft_size returns the smallest 7-smooth size") {
    CHECK(next_fft_size(1) == 1);
    CHECK(next_fft_size(11) == 12);
    CHECK(next_fft_size(13) == 14);
    CHECK(next_fft_size(97) == 98);
    CHECK(next_fft_size(127) == 128);
    CHECK(next_fft_size(959) == 960);
    CHECK(next_fft_size(1031) == 1050);
    CHECK_THROWS_AS(next_fft_size(0), InvalidInput);
}

TEST_CASE("geometry: cyclic is the capture grid; linear is padded and centred") {
    const ConvGeometry c = make_conv_geometry(ConvModel::kCyclic, 16, 12, 8, 8);
    CHECK(c.work_rows == 16);
    CHECK(c.work_cols == 12);
    CHECK(c.crop_row == 0);
    CHECK_THROWS_WITH_AS(make_conv_geometry(ConvModel::kCyclic, 16, 12, 8, 13),
                         doctest::Contains("psf"), InvalidInput);
    const ConvGeometry l = make_conv_geometry(ConvModel::kLinear, 480, 720, 480, 720);
    CHECK(l.work_rows == 960);   // >= 959, 2^6 3 5
    CHECK(l.work_cols == 1440);  // >= 1439
    CHECK(l.crop_row == 240);
    CHECK(l.crop_col == 360);
    CHECK_THROWS_AS(make_conv_geometry(ConvModel::kLinear, 0, 5, 3, 3), InvalidInput);
}

TEST_CASE("pad/crop round trip is exact and crop is the adjoint of pad") {
    const ConvGeometry g = make_conv_geometry(ConvModel::kLinear, 9, 7, 4, 5);
    const Plane p = random_plane(9, 7, 1, -1.0, 1.0);
    CHECK((crop_to_capture(g, pad_to_work(g, p)) == p).all());
    const Plane w = random_plane(g.work_rows, g.work_cols, 2, -1.0, 1.0);
    CHECK_CLOSE(dot(pad_to_work(g, p), w), dot(p, crop_to_capture(g, w)), kAdjointTol);
    CHECK(pad_to_work(g, p).sum() == doctest::Approx(p.sum()).epsilon(1e-14));
}

TEST_CASE("adjoint identity <y, A x> = <A^T y, x> for both models") {
    struct Case {
        ConvModel m;
        int R, C, pr, pc;
    };
    const Case cases[] = {{ConvModel::kCyclic, 8, 8, 3, 3},     {ConvModel::kCyclic, 13, 11, 4, 6},
                          {ConvModel::kCyclic, 16, 12, 16, 12}, {ConvModel::kLinear, 8, 8, 8, 8},
                          {ConvModel::kLinear, 13, 11, 4, 6},   {ConvModel::kLinear, 9, 16, 7, 2}};
    unsigned seed = 40;
    for (const Case& k : cases) {
        const ConvGeometry g = make_conv_geometry(k.m, k.R, k.C, k.pr, k.pc);
        const ConvolutionOperator op(random_plane(k.pr, k.pc, seed++, -1.0, 1.0), g);
        const Plane x = random_plane(g.work_rows, g.work_cols, seed++, -1.0, 1.0);
        const Plane y = random_plane(k.R, k.C, seed++, -1.0, 1.0);
        INFO("model " << int(k.m) << " " << k.R << " x " << k.C);
        CHECK_CLOSE(dot(y, op.apply(x)), dot(op.adjoint(y), x), kAdjointTol);
        const Plane v = random_plane(g.work_rows, g.work_cols, seed++, -1.0, 1.0);
        CHECK_CLOSE(dot(v, op.convolve(x)), dot(op.correlate(v), x), kAdjointTol);
    }
}

TEST_CASE("cyclic operator equals the dense circulant matrix") {
    const Plane psf = random_plane(4, 5, 50, -1.0, 1.0);
    const ConvolutionOperator op(psf, make_conv_geometry(ConvModel::kCyclic, 9, 10, 4, 5));
    const Plane x = random_plane(9, 10, 51, -1.0, 1.0);
    const Plane ref = as_plane(dense_circulant(psf, 9, 10) * as_vector(x), 9, 10);
    CHECK(max_rel_error(op.apply(x), ref) <= kConvVsDirectTol);
}

TEST_CASE("linear operator equals the direct zero-padded convolution of the window") {
    const std::pair<int, int> sizes[] = {{8, 8}, {9, 7}, {13, 13}, {16, 12}};
    const std::pair<int, int> psfs[] = {{3, 3}, {4, 4}, {5, 2}, {8, 7}};
    unsigned seed = 60;
    for (const auto& size : sizes)
        for (const auto& psf_size : psfs) {
            const int R = size.first, C = size.second, pr = psf_size.first, pc = psf_size.second;
            const ConvGeometry g = make_conv_geometry(ConvModel::kLinear, R, C, pr, pc);
            const Plane psf = random_plane(pr, pc, seed++, -1.0, 1.0);
            const Plane x = random_plane(g.work_rows, g.work_cols, seed++, -1.0, 1.0);
            INFO(R << " x " << C << ", psf " << pr << " x " << pc);
            int outside = 0;
            const Plane ref = direct_linear(psf, x, g, outside);
            CHECK(outside == 0);
            CHECK(max_rel_error(ConvolutionOperator(psf, g).apply(x), ref) <= kConvVsDirectTol);
        }
}
