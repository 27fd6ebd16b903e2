// decode/capture/batch and decode/solvers/plan_cache (batch decode): a BatchDecoder makes the
// operator and the closed-form filter once per PSF and grid and reuses them, and every capture
// decodes to exactly the bytes of a fresh decode_capture on it alone (the second code path: no
// cache). Round-robin shares of the captures among ranks cover every index once.
#include <doctest/doctest.h>

#include <vector>

#include "core/errors/error.hpp"
#include "decode/capture/batch.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/plan_cache.hpp"
#include "tests/decode/test_decode_support.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// A cyclic capture of a random scene through `psf`, tiled 2 x 2 (the pipeline crops one period).
Image tiled_capture(const Plane& psf, int n, unsigned seed) {
    const Plane x = random_plane(n, n, seed, 0.0, 1.0);
    const ConvolutionOperator op(psf, make_conv_geometry(ConvModel::kCyclic, n, n, n, n));
    const Plane p = op.apply(x);
    Plane frame(2 * n, 2 * n);
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) frame.block(r * n, c * n, n, n) = p;
    return Image(frame);
}

bool same_image(const Image& a, const Image& b) {
    if (a.channels.size() != b.channels.size()) return false;
    for (std::size_t i = 0; i < a.channels.size(); ++i) {
        if (a.channels[i].rows() != b.channels[i].rows() ||
            a.channels[i].cols() != b.channels[i].cols() || !(a.channels[i] == b.channels[i]).all())
            return false;
    }
    return true;
}

}  // namespace

TEST_CASE("BatchDecoder: plans made once, results identical to a fresh decode of each capture") {
    const int n = 16;
    const Plane psf = random_psf(n, n, 5);
    for (DecodeMethod m : {DecodeMethod::kWiener, DecodeMethod::kTikhonov, DecodeMethod::kTv}) {
        CaptureDecodeOptions o;
        o.decode.method = m;
        o.decode.iterative.max_iterations = 15;
        CaptureDecodeInputs shared;
        shared.psf = Image(psf);
        BatchDecoder batch(shared, o);
        for (unsigned seed : {11u, 12u, 13u}) {
            const Image capture = tiled_capture(psf, n, seed);
            const CaptureDecodeResult got = batch.decode(capture);
            CaptureDecodeInputs alone;
            alone.capture = capture;
            alone.psf = Image(psf);
            const CaptureDecodeResult ref = decode_capture(alone, o);
            INFO(decode_method_name(m), " seed ", seed);
            CHECK(same_image(got.estimate, ref.estimate));
            CHECK(got.summary.channels[0].residual == ref.summary.channels[0].residual);
            CHECK(got.summary.channels[0].objective == ref.summary.channels[0].objective);
        }
        CHECK(batch.decoded() == 3);
        CHECK(batch.plans().operators_built() == 1);
        // Closed-form methods build their filter once; TV has none.
        CHECK(batch.plans().filters_built() == (m == DecodeMethod::kTv ? 0 : 1));
    }
}

TEST_CASE("DecodePlanCache: a new grid or PSF builds a new plan, the same one is reused") {
    const int n = 16;
    const Plane psf_a = random_psf(n, n, 7);
    const Plane psf_b = random_psf(n, n, 8);
    DecodePlanCache cache;
    DecodeOptions o;
    const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, n, n, n, n);
    const ConvGeometry g_linear = make_conv_geometry(ConvModel::kLinear, n, n, n, n);
    const auto f1 = cache.filter(psf_a, g, o);
    CHECK(cache.filter(psf_a, g, o) == f1);
    CHECK(cache.filters_built() == 1);
    CHECK(cache.filter(psf_b, g, o) != f1);
    CHECK(cache.filter(psf_a, g_linear, o) != f1);
    o.wiener.nsr = 0.5;
    CHECK(cache.filter(psf_a, g, o) != f1);
    CHECK(cache.filters_built() == 4);
    const auto op = cache.conv_operator(psf_a, g);
    CHECK(cache.conv_operator(psf_a, g) == op);
    CHECK(cache.conv_operator(psf_b, g) != op);
    CHECK(cache.operators_built() == 2);
    // Whole frames (--crop none) of two sizes in one batch: one filter per grid.
    CaptureDecodeOptions co;
    co.crop.mode = CropMode::kNone;
    CaptureDecodeInputs shared;
    shared.psf = Image(psf_a);
    BatchDecoder batch(shared, co);
    batch.decode(tiled_capture(psf_a, n, 1));
    batch.decode(tiled_capture(psf_a, n, 2));
    CHECK(batch.plans().filters_built() == 1);
    batch.decode(Image(Plane(random_plane(3 * n, 3 * n, 4, 0.0, 1.0))));
    CHECK(batch.plans().filters_built() == 2);
}

TEST_CASE("batch_share: round robin by index, every capture on exactly one rank") {
    for (int size : {1, 2, 3, 5}) {
        std::vector<int> seen(11, 0);
        for (int rank = 0; rank < size; ++rank)
            for (std::size_t i : batch_share(11, rank, size)) {
                CHECK(static_cast<int>(i % size) == rank);
                ++seen[i];
            }
        for (int s : seen) CHECK(s == 1);
    }
    CHECK(batch_share(2, 2, 3).empty());
    CHECK_THROWS_AS(batch_share(3, 0, 0), InvalidInput);
    CHECK_THROWS_AS(batch_share(3, 3, 3), InvalidInput);
}
