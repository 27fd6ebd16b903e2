// decode/capture/capture_defaults and the pipeline's auto settings: each rule on inputs whose
// answer is known by construction (a quantile counted by hand, a lensless-sized PSF, a mask's
// period, a signed capture), and each choice recorded with its reason.
#include <doctest/doctest.h>

#include <string>

#include "decode/capture/capture_defaults.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/solvers/decode_method.hpp"
#include "tests/decode/test_decode_support.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

const ChosenSetting* find(const CaptureDecodeSummary& s, const std::string& name) {
    for (const ChosenSetting& c : s.chosen)
        if (c.name == name) return &c;
    return nullptr;
}

CaptureDecodeOptions all_auto() {
    CaptureDecodeOptions o;
    o.model_auto = o.crop_auto = o.nonnegative_auto = true;
    o.background = BackgroundMode::kAuto;
    return o;
}

}  // namespace

TEST_CASE("psf_floor is the 5 % quantile, 0 when not positive; whole_numbers") {
    Plane p(10, 10);
    for (int i = 0; i < 100; ++i) p.data()[i] = 1000 - 10 * i;  // 1000, 990, ..., 10
    // 5 % of 99 gaps is element 4 of the sorted values 10, 20, 30, 40, 50, ...
    CHECK(psf_floor(p) == 50.0);
    CHECK(psf_floor(Plane(-p)) == 0.0);
    CHECK(whole_numbers(p));
    p(3, 3) += 0.5;
    CHECK_FALSE(whole_numbers(p));
}

TEST_CASE("auto: a measured PSF in counts that covers the capture is linear, its floor off both") {
    const int n = 24;
    Plane psf = Plane::Constant(n, n, 7.0);  // a dark floor of 7 counts
    psf(3, 4) = 900;
    psf(15, 20) = 500;
    psf(9, 2) = 300;
    const Plane scene = random_plane(n, n, 4, 0.0, 50.0).round();
    CaptureDecodeInputs in;
    in.capture = Image(Plane(scene + 7.0));
    in.psf = Image(psf);
    CaptureDecodeOptions o = all_auto();
    o.decode.method = DecodeMethod::kTv;
    o.decode.iterative.max_iterations = 3;
    const CaptureDecodeResult r = decode_capture(in, o);
    REQUIRE(find(r.summary, "model"));
    CHECK(find(r.summary, "model")->value == "linear");
    CHECK(find(r.summary, "crop")->value == "none");
    CHECK(find(r.summary, "background")->value == "7");
    CHECK(r.summary.background == 7.0);  // off the capture too: both are counts
    CHECK(r.summary.psf_background == 7.0);
    CHECK(find(r.summary, "nonnegative")->value == "true");
    CHECK(r.summary.model == ConvModel::kLinear);
    CHECK(r.summary.window.rows == n);

    // A float capture (not counts): the floor comes off the PSF only.
    in.capture = Image(Plane(scene + 7.25));
    const CaptureDecodeResult f = decode_capture(in, o);
    CHECK_FALSE(f.summary.background.has_value());
    CHECK(f.summary.psf_background == 7.0);
    // A signed capture (a smooth ramp through 0: no noise to excuse it) is not an intensity.
    Plane ramp(n, n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) ramp(r, c) = 4.0 * c - 30.0;
    in.capture = Image(ramp);
    CHECK(find(decode_capture(in, o).summary, "nonnegative")->value == "false");
}

TEST_CASE("auto: a mask's period stays cyclic with no background; a smaller PSF is a period") {
    const int n = 16;
    const Plane psf = random_psf(n, n, 2);
    CaptureDecodeInputs in;
    in.capture = Image(random_plane(n, n, 3, 0.0, 1.0));
    in.psf = Image(psf);
    in.psf_one_period = true;
    const CaptureDecodeResult r = decode_capture(in, all_auto());
    CHECK(find(r.summary, "model")->value == "cyclic");
    CHECK(find(r.summary, "crop")->value == "none");  // the capture is one period
    CHECK(find(r.summary, "background")->value == "none");
    CHECK_FALSE(find(r.summary, "nonnegative"));  // wiener reads no non-negativity

    in.capture = Image(random_plane(2 * n, 2 * n, 5, 0.0, 1.0));
    in.psf_one_period = false;
    const CaptureDecodeResult t = decode_capture(in, all_auto());
    CHECK(find(t.summary, "model")->value == "cyclic");
    CHECK(find(t.summary, "crop")->value == "center");
    CHECK(t.summary.window.rows == n);
    CHECK(find(t.summary, "background")->value == "none");
}

TEST_CASE("given settings are not replaced and nothing is recorded for them") {
    const int n = 16;
    CaptureDecodeInputs in;
    in.capture = Image(random_plane(n, n, 3, 0.0, 1.0));
    in.psf = Image(random_psf(n, n, 2));
    CaptureDecodeOptions o;  // the library's own defaults: nothing automatic
    const CaptureDecodeResult r = decode_capture(in, o);
    CHECK(r.summary.chosen.empty());
    CHECK(r.summary.model == ConvModel::kCyclic);
}
