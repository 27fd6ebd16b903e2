// decode/capture/decode_request: the typed request sorted into the chosen method's options, and the
// refusal of a parameter the method does not read, naming the request's fields (field_ref) and
// never a face's spelling.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "decode/capture/decode_request.hpp"
#include "decode/solvers/decode_method.hpp"

using namespace pinmask;

namespace {

std::string refusal(const DecodeRequest& r, const std::vector<GivenParameter>& given) {
    try {
        refuse_unused_parameters(r, given);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST_CASE("decode_request: each method's options get the parameters it reads, and only those") {
    DecodeRequest r;
    r.nsr = 0.5;
    r.lambda = 0.25;
    r.regulariser = TikhonovRegulariser::kGradient;
    r.eps = 3.0;
    r.nonnegative = true;
    r.iterations = 17;
    r.tolerance = 1e-6;
    r.model = ConvModel::kLinear;
    r.method_auto = false;  // a method given

    r.method = DecodeMethod::kWiener;
    DecodeOptions d = decode_options(r);
    CHECK(d.method == DecodeMethod::kWiener);
    CHECK(d.model == ConvModel::kLinear);
    CHECK(d.wiener.nsr == 0.5);
    CHECK(d.tikhonov.lambda == DecodeOptions{}.tikhonov.lambda);
    CHECK(d.iterative.max_iterations == DecodeOptions{}.iterative.max_iterations);

    r.method = DecodeMethod::kTikhonov;
    d = decode_options(r);
    CHECK(d.tikhonov.lambda == 0.25);
    CHECK(d.tikhonov.regulariser == TikhonovRegulariser::kGradient);
    CHECK(d.wiener.nsr == DecodeOptions{}.wiener.nsr);

    r.method = DecodeMethod::kTv;
    d = decode_options(r);
    CHECK(d.tv.lambda == 0.25);
    CHECK(d.tv.nonnegative);
    CHECK(d.iterative.max_iterations == 17);
    CHECK(d.iterative.tolerance == 1e-6);
    CHECK(d.iterative.record_history == DecodeOptions{}.iterative.record_history);

    r.method = DecodeMethod::kTvqc;
    d = decode_options(r);
    REQUIRE(d.tvqc.eps.has_value());
    CHECK(*d.tvqc.eps == 3.0);
    CHECK(d.tvqc.nonnegative);

    r.method = DecodeMethod::kRichardsonLucy;
    d = decode_options(r);
    CHECK(d.iterative.max_iterations == 17);
    CHECK(d.tv.lambda == DecodeOptions{}.tv.lambda);
}

TEST_CASE("decode_request: the pipeline options carry crop, background and the rest as given") {
    DecodeRequest r;
    r.crop = {CropMode::kCorner, 4, 9};
    r.background = {BackgroundMode::kValue, 2.5};
    r.downsample = 2;
    r.normalize = NormalizeMode::kL2;
    r.precision = Precision::kDouble;
    r.threads = 3;
    const CaptureDecodeOptions o = capture_decode_options(r);
    CHECK(o.crop.mode == CropMode::kCorner);
    CHECK(o.crop.row == 4);
    CHECK(o.crop.col == 9);
    CHECK(o.background == BackgroundMode::kValue);
    CHECK(o.background_value == 2.5);
    CHECK(o.downsample == 2);
    CHECK(o.normalize == NormalizeMode::kL2);
    CHECK(o.precision == Precision::kDouble);
    CHECK(o.threads == 3);
    CHECK(o.decode.method == DecodeMethod::kWiener);
}

TEST_CASE("decode_request: a parameter the method ignores is refused by its field name") {
    DecodeRequest r;
    r.method = DecodeMethod::kTv;
    CHECK(refusal(r, {{MethodParameter::kNsr, "0.1"}}) ==
          "`nsr` = 0.1: is not used by `method` tv (only by wiener); remove it or choose that "
          "method");
    r.method = DecodeMethod::kWiener;
    CHECK(refusal(r, {{MethodParameter::kIterations, "5"}})
              .find("`iterations` = 5: is not used by `method` wiener (only by tv, tvqc, "
                    "richardson-lucy)") == 0);
    CHECK(refusal(r, {{MethodParameter::kLambda, "1"}}).find("(only by tikhonov, tv)") !=
          std::string::npos);
    CHECK(refusal(r, {{MethodParameter::kNsr, "0.1"}}) == "no error");

    // Every parameter's field is a DecodeRequest field name, and some method reads it.
    for (const MethodParameter p : kMethodParameters) {
        const std::string field = method_parameter_field(p);
        CHECK(field != "?");
        bool read = false;
        for (const DecodeMethod m : kDecodeMethods) {
            DecodeOptions probe;
            probe.method = m;
            read = read || write_method_parameter(probe, p, DecodeRequest{});
        }
        CHECK(read);
    }

    r.method = DecodeMethod::kTikhonov;
    r.lambda = 0.0;
    r.lambda_auto = false;  // a weight given (the default chooses one from the capture)
    const std::string m = refusal(r, {});
    CHECK(m.find("`lambda` = ") == 0);
    CHECK(m.find("use `method` wiener `nsr` 0 for the floored inverse") != std::string::npos);
}

TEST_CASE("decode_request: method auto fills wiener's and tv's options; a given parameter picks") {
    DecodeRequest r;  // the faces' defaults: method auto
    REQUIRE(r.method_auto);
    r.nsr = 0.5;
    r.nsr_auto = false;
    r.lambda = 0.25;
    r.lambda_auto = false;
    r.iterations = 17;
    const CaptureDecodeOptions o = capture_decode_options(r);
    CHECK(o.method_auto);
    CHECK(o.decode.wiener.nsr == 0.5);
    CHECK(o.decode.tv.lambda == 0.25);
    CHECK(o.decode.iterative.max_iterations == 17);
    CHECK(o.decode.tikhonov.lambda == DecodeOptions{}.tikhonov.lambda);

    // Nothing given: still auto.
    DecodeRequest a;
    resolve_implied_method(a, {}, false);
    CHECK(a.method_auto);
    // A parameter only wiener reads, or an NSR map: wiener; one only tv reads: tv.
    a = DecodeRequest{};
    resolve_implied_method(a, {{MethodParameter::kNsr, "0.1"}}, false);
    CHECK_FALSE(a.method_auto);
    CHECK(a.method == DecodeMethod::kWiener);
    CHECK(a.method_implied_by == "nsr");
    CHECK(capture_decode_options(a).method_implied_by == "nsr");
    a = DecodeRequest{};
    resolve_implied_method(a, {}, true);
    CHECK(a.method == DecodeMethod::kWiener);
    CHECK(a.method_implied_by == "nsr_map");
    for (MethodParameter p : {MethodParameter::kLambda, MethodParameter::kNonnegative,
                              MethodParameter::kIterations, MethodParameter::kTolerance}) {
        a = DecodeRequest{};
        resolve_implied_method(a, {{p, "1"}}, false);
        CHECK(a.method == DecodeMethod::kTv);
        CHECK(a.method_implied_by == method_parameter_field(p));
        CHECK(refusal(a, {{p, "1"}}) == "no error");
    }
    // A parameter neither reads, or two that disagree: refused, naming them and the method.
    const auto resolve_refusal = [](const std::vector<GivenParameter>& given, bool map) {
        DecodeRequest q;
        try {
            resolve_implied_method(q, given, map);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(resolve_refusal({{MethodParameter::kRegulariser, "gradient"}}, false) ==
          "`regulariser` = gradient: is not used by `method` auto (wiener or tv, chosen from the "
          "capture; only by tikhonov); give `method` tikhonov");
    CHECK(resolve_refusal({{MethodParameter::kEps, "3"}}, false).find("give `method` tvqc") !=
          std::string::npos);
    CHECK(resolve_refusal({{MethodParameter::kNsr, "0.1"}, {MethodParameter::kIterations, "5"}},
                          false) ==
          "`iterations` = 5: is read by tv but `nsr` 0.1 is read by wiener only; give `method` "
          "to say which");
    CHECK(resolve_refusal({{MethodParameter::kLambda, "1"}}, true).find("`lambda` = 1") == 0);
    // A given method is left alone (refuse_unused_parameters judges its parameters).
    DecodeRequest g;
    g.method_auto = false;
    g.method = DecodeMethod::kTikhonov;
    resolve_implied_method(g, {{MethodParameter::kRegulariser, "gradient"}}, false);
    CHECK(g.method == DecodeMethod::kTikhonov);
    CHECK(g.method_implied_by.empty());
}
