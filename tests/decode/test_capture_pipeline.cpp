// decode/capture/capture_pipeline: the library call behind `pinmask decode` against decode_plane on
// the window it must pick, its option checks (field, value, rule), precision choice, and results
// that do not depend on the FFT thread count.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/solvers/decode_method.hpp"
#include "tests/decode/test_decode_support.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// A 2 x 2 tiling of one period's cyclic capture: any full period decodes the scene.
CaptureDecodeInputs tiled(int n, unsigned seed) {
    const Plane psf = random_psf(n, n, seed);
    const Plane x = random_plane(n, n, seed + 1, 0.0, 1.0);
    const ConvolutionOperator op(psf, make_conv_geometry(ConvModel::kCyclic, n, n, n, n));
    const Plane p = op.apply(x);
    Plane frame(2 * n, 2 * n);
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) frame.block(r * n, c * n, n, n) = p;
    CaptureDecodeInputs in;
    in.capture = Image(frame);
    in.psf = Image(psf);
    return in;
}

}  // namespace

TEST_CASE("decode_capture = decode_plane on the centred period (Wiener and TV)") {
    const int n = 16;
    const CaptureDecodeInputs in = tiled(n, 3);
    for (DecodeMethod m : {DecodeMethod::kWiener, DecodeMethod::kTv}) {
        CaptureDecodeOptions o;
        o.decode.method = m;
        o.decode.iterative.max_iterations = 20;
        const CaptureDecodeResult r = decode_capture(in, o);
        CHECK(r.summary.window.row == n / 2);
        CHECK(r.summary.window.col == n / 2);
        const Plane window = in.capture.channels[0].block(n / 2, n / 2, n, n);
        const Plane psf = in.psf.channels[0] / in.psf.channels[0].sum();  // as the pipeline
        const Plane ref = decode_plane(window, psf, o.decode).image;
        INFO(std::string(decode_method_name(m)));
        CHECK((r.estimate.channels.at(0) == ref).all());
        CHECK_FALSE(r.summary.single_precision);  // 16 x 16 < 256 x 256
        CHECK(r.summary.channels.size() == 1);
        CHECK(r.summary.channels[0].image.size() == 0);  // moved into the estimate
    }
}

TEST_CASE("CaptureDecodeOptions::validate names the field, the value and the rule") {
    auto fails = [](const CaptureDecodeOptions& o, const char* field) {
        CHECK_THROWS_WITH_AS(o.validate(), doctest::Contains(field), InvalidInput);
    };
    CaptureDecodeOptions o;
    o.downsample = 13;
    fails(o, "downsample");
    o = {};
    o.threads = -1;
    fails(o, "threads");
    o = {};
    o.background = BackgroundMode::kValue;
    o.background_value = std::nan("");
    fails(o, "background");
    o = {};
    o.decode.method = DecodeMethod::kTv;
    o.decode.iterative.max_iterations = 0;
    fails(o, "iterations");
    o.decode.method = DecodeMethod::kWiener;  // closed form: iterations are not read
    CHECK_NOTHROW(o.validate());
    CHECK_THROWS_WITH_AS(parse_decode_method("rl"), doctest::Contains("richardson-lucy"),
                         InvalidInput);
    CHECK(parse_decode_method("richardson-lucy") == DecodeMethod::kRichardsonLucy);
    CHECK_THROWS_AS(parse_precision("half"), InvalidInput);
}

TEST_CASE("a background beyond the capture's magnitude is refused, naming background") {
    CaptureDecodeInputs in = tiled(16, 5);
    CaptureDecodeOptions o;
    o.background = BackgroundMode::kValue;
    o.background_value = 1e308;
    CHECK_THROWS_WITH_AS(decode_capture(in, o), doctest::Contains("background"), InvalidInput);
    o.background = BackgroundMode::kCorner;  // no PSF counts (a synthesised PSF)
    CHECK_THROWS_WITH_AS(decode_capture(in, o), doctest::Contains("background"), InvalidInput);
}

TEST_CASE("precision auto: float32 from 256 x 256 decoded pixels for every method") {
    CaptureDecodeInputs in;
    in.capture = Image(random_plane(256, 256, 7, 0.0, 1.0));
    in.psf = Image(random_psf(8, 8, 8));
    CaptureDecodeOptions o;
    o.crop.mode = CropMode::kNone;
    o.decode.iterative.max_iterations = 2;
    o.decode.tvqc.eps = 1.0;
    for (DecodeMethod m : kDecodeMethods) {
        o.decode.method = m;
        INFO(decode_method_name(m));
        o.precision = Precision::kAuto;
        CHECK(decode_capture(in, o).summary.single_precision);
        o.precision = Precision::kDouble;
        CHECK_FALSE(decode_capture(in, o).summary.single_precision);
    }
    CaptureDecodeInputs small = in;  // 255 x 256: below the rule, double
    small.capture = Image(random_plane(255, 256, 7, 0.0, 1.0));
    o.precision = Precision::kAuto;
    CHECK_FALSE(decode_capture(small, o).summary.single_precision);
}

TEST_CASE("precision: captures near float's range decode in float; a cancelling PSF does not") {
    CaptureDecodeInputs in;
    in.capture = Image(random_plane(256, 256, 17, 0.0, 1.0));
    in.psf = Image(random_psf(8, 8, 18));
    CaptureDecodeOptions o;
    o.crop.mode = CropMode::kNone;
    o.decode.iterative.max_iterations = 5;
    o.decode.tvqc.eps = 1.0;
    // Counts at 3e38 (FLT_MAX 3.4e38) and 1e100 (beyond float): the solvers divide by the
    // largest magnitude first, so float32 runs and agrees with double to float rounding (5e-4
    // covers the iterative methods' kSingle*Tol of tests/decode/test_precision.cpp).
    for (double k : {3e38, 1e100}) {
        for (DecodeMethod m : kDecodeMethods) {
            CaptureDecodeInputs big = in;
            big.capture.channels[0] *= k;
            o.decode.method = m;
            o.decode.tvqc.eps = 1.0 * k;
            o.decode.tv.lambda = 1e-3 * k;
            o.precision = Precision::kSingle;
            const CaptureDecodeResult s = decode_capture(big, o);
            o.precision = Precision::kDouble;
            const CaptureDecodeResult d = decode_capture(big, o);
            INFO(decode_method_name(m) << " scale " << k);
            REQUIRE(is_all_finite(s.estimate.channels[0]));
            const Plane& a = s.estimate.channels[0];
            const Plane& b = d.estimate.channels[0];
            CHECK(std::sqrt((a - b).square().sum() / b.square().sum()) <= 1e-3);
        }
    }
    // A PSF whose values cancel (sum|a| / sum a = 2e40): auto falls back to double and says
    // why; single is refused, naming the field.
    Plane cancel(1, 3);
    cancel << 1e40, -1e40, 1.0;
    in.psf = Image(cancel);
    o.decode.method = DecodeMethod::kWiener;
    o.precision = Precision::kAuto;
    const CaptureDecodeResult r = decode_capture(in, o);
    CHECK_FALSE(r.summary.single_precision);
    bool noted = false;
    for (const std::string& line : r.summary.notes)
        noted = noted || line.find("double instead of float32") != std::string::npos;
    CHECK(noted);
    o.precision = Precision::kSingle;
    CHECK_THROWS_WITH_AS(decode_capture(in, o), doctest::Contains("precision"), InvalidInput);
}

TEST_CASE(
    "results do not depend on the FFT thread count (512 x 512, tv/tvqc/rl, both precisions)") {
    const int n = std::getenv("PINMASK_SANITIZED") ? 512 : 512;  // the threaded size itself
    CaptureDecodeInputs in;
    in.capture = Image(random_plane(n, n, 9, 0.0, 1.0));
    in.psf = Image(random_psf(16, 16, 10));
    for (Precision p : {Precision::kDouble, Precision::kSingle})
        for (DecodeMethod m :
             {DecodeMethod::kTv, DecodeMethod::kTvqc, DecodeMethod::kRichardsonLucy}) {
            CaptureDecodeOptions o;
            o.crop.mode = CropMode::kNone;
            o.precision = p;
            o.decode.method = m;
            o.decode.tvqc.eps = 10.0;
            o.decode.iterative.max_iterations = 3;
            o.threads = 1;
            const CaptureDecodeResult one = decode_capture(in, o);
            CHECK(one.summary.fft_threads == 1);
            o.threads = 2;
            const CaptureDecodeResult two = decode_capture(in, o);
            CHECK(two.summary.fft_threads == 2);
            CHECK((one.estimate.channels[0] == two.estimate.channels[0]).all());
        }
    set_fft_threads(1);
}
