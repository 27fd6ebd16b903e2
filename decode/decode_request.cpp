#include "decode/decode_request.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/units.hpp"
#include "decode/decode_method.hpp"
#include "decode/decode_modes.hpp"

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

const char* method_flag_name(MethodFlag f) {
    switch (f) {
        case MethodFlag::kNsr:
            return "--nsr";
        case MethodFlag::kLambda:
            return "--lambda";
        case MethodFlag::kRegulariser:
            return "--regulariser";
        case MethodFlag::kEps:
            return "--eps";
        case MethodFlag::kNoiseSigma:
            return "--noise-sigma";
        case MethodFlag::kNonnegative:
            return "--nonneg";
        case MethodFlag::kIterations:
            return "--iters";
        case MethodFlag::kTolerance:
            return "--tol";
    }
    return "?";
}

bool write_method_flag(DecodeOptions& d, MethodFlag f, const DecodeRequest& r) {
    const DecodeMethod m = d.method;
    switch (f) {
        case MethodFlag::kNsr:
            if (m != DecodeMethod::kWiener) return false;
            d.wiener.nsr = r.nsr;
            return true;
        case MethodFlag::kLambda:
            if (m == DecodeMethod::kTikhonov) d.tikhonov.lambda = r.lambda;
            if (m == DecodeMethod::kTv) d.tv.lambda = r.lambda;
            return m == DecodeMethod::kTikhonov || m == DecodeMethod::kTv;
        case MethodFlag::kRegulariser:
            if (m != DecodeMethod::kTikhonov) return false;
            d.tikhonov.regulariser = parse_regulariser(r.regulariser, "--regulariser");
            return true;
        case MethodFlag::kEps:
            if (m != DecodeMethod::kTvqc) return false;
            d.tvqc.eps = r.eps;
            return true;
        case MethodFlag::kNoiseSigma:
            if (m != DecodeMethod::kTvqc) return false;
            d.tvqc.noise_sigma = r.noise_sigma;
            return true;
        case MethodFlag::kNonnegative:
            if (m == DecodeMethod::kTv) d.tv.nonnegative = r.nonnegative;
            if (m == DecodeMethod::kTvqc) d.tvqc.nonnegative = r.nonnegative;
            return m == DecodeMethod::kTv || m == DecodeMethod::kTvqc;
        case MethodFlag::kIterations:
            if (!is_iterative(m)) return false;
            d.iterative.max_iterations = r.iterations;
            return true;
        case MethodFlag::kTolerance:
            if (!is_iterative(m)) return false;
            d.iterative.tolerance = r.tolerance;
            return true;
    }
    return false;
}

void refuse_unused_flags(const DecodeRequest& r, const std::vector<GivenFlag>& given) {
    const DecodeMethod m = parse_decode_method(r.method, "--method");
    for (const GivenFlag& g : given) {
        DecodeOptions probe;
        probe.method = m;
        if (write_method_flag(probe, g.flag, r)) continue;
        std::string users;
        for (DecodeMethod other : kDecodeMethods) {
            probe.method = other;
            if (write_method_flag(probe, g.flag, r))
                users += (users.empty() ? "" : ", ") + std::string(decode_method_name(other));
        }
        throw invalid_field(method_flag_name(g.flag), g.value,
                            std::string("is not used by --method ") + decode_method_name(m) +
                                " (only by " + users + "); remove it or choose that method");
    }
    if (m == DecodeMethod::kTikhonov && !(r.lambda > 0.0)) {
        throw invalid_field("--lambda", std::to_string(r.lambda),
                            "must be > 0 for tikhonov: lambda 0 is the unregularised inverse "
                            "filter, which multiplies noise by 1/|H| at the PSF's spectral "
                            "near-zeros (use --method wiener --nsr 0 for the floored inverse)");
    }
}

DecodeOptions decode_options(const DecodeRequest& r) {
    DecodeOptions d;
    d.method = parse_decode_method(r.method, "--method");
    d.model = parse_conv_model(r.model, "--model");
    for (MethodFlag f : kMethodFlags) write_method_flag(d, f, r);
    // Per-iteration records cost an objective each iteration; only --stats and --json show them.
    d.iterative.record_history = !r.stats.empty() || r.json;
    return d;
}

CaptureDecodeOptions capture_decode_options(const DecodeRequest& r) {
    CaptureDecodeOptions o;
    o.crop = parse_crop(r.crop);
    const DecodeBackground bg = parse_background(r.background);
    o.background = bg.mode;
    o.background_value = bg.value;
    o.downsample = r.downsample;
    o.normalize = parse_normalize_mode(r.normalize, "--normalize");
    o.decode = decode_options(r);
    o.precision = parse_precision(r.precision, "--precision");
    o.threads = r.threads;
    return o;
}

DecodeBackground parse_background(const std::string& s) {
    for (const auto& [mode, name] : kBackgroundModeNames)
        if (mode != BackgroundMode::kValue && s == name) return {mode, 0.0};
    return {BackgroundMode::kValue, parse_number(s, "--background")};
}

std::optional<double> parse_scale(const std::string& s) {
    if (s == "max") return std::nullopt;
    const double v = parse_number(s, "--scale");
    if (!(v > 0.0)) throw invalid_field("--scale", s, "must be max or a factor > 0");
    return v;
}

}  // namespace pinmask
