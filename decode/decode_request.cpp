#include "decode/decode_request.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/units.hpp"
#include "decode/decode_method.hpp"

namespace pinmask {

CropSpec parse_crop(const std::string& s) {
    if (s == "center" || s == "centre") return {CropMode::kCenter};
    if (s == "none") return {CropMode::kNone};
    const auto comma = s.find(',');
    if (comma != std::string::npos) {
        const double x = parse_number(s.substr(0, comma), "--crop X");
        const double y = parse_number(s.substr(comma + 1), "--crop Y");
        // Range first: casting a double outside int's range is undefined behaviour.
        const auto whole = [](double v) { return std::fabs(v) <= 1e9 && v == std::floor(v); };
        if (whole(x) && whole(y))
            return {CropMode::kCorner, static_cast<int>(y), static_cast<int>(x)};
    }
    throw invalid_field("--crop", s, "must be center, none or X,Y (integer pixel corner)");
}

DecodeOptions decode_options(const DecodeRequest& r) {
    DecodeOptions d;
    d.method = parse_decode_method(r.method, "--method");
    d.model = r.model == "linear" ? ConvModel::kLinear : ConvModel::kCyclic;
    d.nsr = r.nsr;
    d.lambda = r.lambda;
    d.regulariser = r.regulariser == "gradient" ? TikhonovRegulariser::kGradient
                                                : TikhonovRegulariser::kIdentity;
    d.eps = r.eps;
    d.noise_sigma = r.noise_sigma;
    d.nonnegative = r.nonnegative;
    d.max_iterations = r.iterations;
    d.tolerance = r.tolerance;
    d.record_history = true;
    return d;
}

CaptureDecodeOptions capture_decode_options(const DecodeRequest& r) {
    CaptureDecodeOptions o;
    o.crop = parse_crop(r.crop);
    const DecodeBackground bg = parse_background(r.background);
    o.background = bg.mode == "none"     ? BackgroundMode::kNone
                   : bg.mode == "corner" ? BackgroundMode::kCorner
                                         : BackgroundMode::kValue;
    o.background_value = bg.value;
    o.downsample = r.downsample;
    o.normalize = r.normalize == "l2" ? NormalizeMode::kL2 : NormalizeMode::kNone;
    o.decode = decode_options(r);
    o.precision = parse_precision(r.precision, "--precision");
    o.threads = r.threads;
    return o;
}

DecodeBackground parse_background(const std::string& s) {
    if (s == "none" || s == "corner") return {s, 0.0};
    return {"value", parse_number(s, "--background")};
}

std::optional<double> parse_scale(const std::string& s) {
    if (s == "max") return std::nullopt;
    const double v = parse_number(s, "--scale");
    if (!(v > 0.0)) throw invalid_field("--scale", s, "must be max or a factor > 0");
    return v;
}

}  // namespace pinmask
