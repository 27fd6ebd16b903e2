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

TEST_CASE("border_fill: the border band's mean magnitude over the capture's, counted by hand") {
    // 32 x 48: the band is 32 / 16 = 2 px wide; 32 * 48 - 28 * 44 = 304 band pixels.
    Plane lit = Plane::Constant(32, 48, 3.0);
    CHECK(border_fill(lit) == doctest::Approx(1.0).epsilon(1e-15));
    Plane dark_band = lit;
    dark_band.block(2, 2, 28, 44).setConstant(0.0);  // only the band lit: 304 px of 3
    // mean = 304 * 3 / 1536; band mean = 3: fill = 1536 / 304.
    CHECK(border_fill(dark_band) == doctest::Approx(1536.0 / 304.0).epsilon(1e-15));
    Plane centre = Plane::Zero(32, 48);
    centre.block(10, 10, 8, 8).setConstant(-5.0);  // magnitudes: a signed capture reads the same
    CHECK(border_fill(centre) == 0.0);
    CHECK(border_fill(Plane(Plane::Zero(32, 48))) == 0.0);
    CHECK(border_fill(Plane(Plane::Constant(2, 40, 1.0))) == 0.0);  // the band covers it
    // An image: the largest over the channels.
    Image two;
    two.channels = {centre, lit};
    CHECK(border_fill(two) == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(auto_method_is_tv(true));
    CHECK_FALSE(auto_method_is_tv(false));
}

TEST_CASE("auto method: tv on the linear model, lit to the edges or dark, wiener on the cyclic") {
    const int n = 32;
    CaptureDecodeInputs in;
    in.psf = Image(random_psf(n, n, 7));                  // covers the capture: linear
    in.capture = Image(random_plane(n, n, 8, 1.0, 2.0));  // lit to the edges
    CaptureDecodeOptions o = all_auto();
    o.method_auto = true;
    o.decode.wiener.automatic = o.decode.tv.automatic = true;  // the faces' default weights
    o.decode.iterative.max_iterations = 3;
    const CaptureDecodeResult tv = decode_capture(in, o);
    CHECK(find(tv.summary, "model")->value == "linear");
    REQUIRE(find(tv.summary, "method"));
    CHECK(find(tv.summary, "method")->value == "tv");
    CHECK(find(tv.summary, "method")->reason.find("linear model") != std::string::npos);
    CHECK(tv.summary.method == DecodeMethod::kTv);
    CHECK(find(tv.summary, "nonnegative")->value == "true");  // read for the method chosen
    CHECK(tv.summary.channels.front().iterations >= 1);
    CHECK(tv.summary.warnings.empty());  // tv at its automatic weight: nothing to advise

    // The same sizes with the light in the middle of a dark frame: still tv (the light
    // beyond the sensor is unknown, not zero), the border's share in the reason.
    Plane middle = Plane::Zero(n, n);
    middle.block(12, 12, 8, 8) = random_plane(8, 8, 9, 1.0, 2.0);
    in.capture = Image(middle);
    const CaptureDecodeResult w = decode_capture(in, o);
    CHECK(find(w.summary, "method")->value == "tv");
    CHECK(find(w.summary, "method")->reason.find("border band averages 0 %") != std::string::npos);
    CHECK(w.summary.warnings.empty());

    // A lit frame on the cyclic model (a mask's period): wiener.
    in.capture = Image(random_plane(n, n, 8, 1.0, 2.0));
    in.psf_one_period = true;
    const CaptureDecodeResult c = decode_capture(in, o);
    CHECK(find(c.summary, "model")->value == "cyclic");
    CHECK(find(c.summary, "method")->value == "wiener");

    // The decode is the given method's, bytes and all: auto adds only the record.
    in.psf_one_period = false;
    CaptureDecodeOptions given = o;
    given.method_auto = false;
    given.decode.method = DecodeMethod::kTv;
    const CaptureDecodeResult same = decode_capture(in, given);
    CHECK_FALSE(find(same.summary, "method"));
    CHECK((same.estimate.channels.front() == tv.estimate.channels.front()).all());

    // A method implied by a given parameter is recorded with that parameter as the reason.
    CaptureDecodeOptions implied = given;
    implied.decode.method = DecodeMethod::kWiener;
    implied.method_implied_by = "nsr";
    const CaptureDecodeResult i = decode_capture(in, implied);
    CHECK(find(i.summary, "method")->value == "wiener");
    CHECK(find(i.summary, "method")->reason.find("`nsr` given") == 0);
    // ... and keeps wiener's advice on this frame-filling linear capture, naming tv.
    REQUIRE(i.summary.warnings.size() == 1);
    CHECK(i.summary.warnings.front().find("`method` tv") != std::string::npos);
}
