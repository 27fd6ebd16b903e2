#include "cli/decode_output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/units.hpp"
#include "decode/decode_method.hpp"
#include "decode/decode_modes.hpp"

namespace pinmask::cli {
namespace {

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

nlohmann::json axis_json(const AxisPeriodCheck& a) {
    nlohmann::json j = {
        {"size_px", a.size_px}, {"expected_px", a.expected_px}, {"checked", a.checked}};
    if (!a.checked) {
        j["skip_reason"] = a.skip_reason;
        return j;
    }
    j["found"] = a.found;
    if (a.found) {
        j["measured_px"] = a.measured_px;
        j["peak_value"] = a.peak_value;
        j["peak_rise"] = a.peak_rise;
    }
    j["matches"] = a.matches;
    return j;
}

}  // namespace

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
    d.iterative.record_history = true;
    return d;
}

CaptureDecodeOptions capture_decode_options(const DecodeRequest& r) {
    CaptureDecodeOptions o;
    o.crop = parse_crop(r.crop);
    const Background bg = parse_background(r.background);
    o.background = bg.mode;
    o.background_value = bg.value;
    o.downsample = r.downsample;
    o.normalize = parse_normalize_mode(r.normalize, "--normalize");
    o.decode = decode_options(r);
    o.precision = parse_precision(r.precision, "--precision");
    o.threads = r.threads;
    return o;
}

void add_summary_json(nlohmann::json& stats, nlohmann::json& timings, const DecodeRequest& r,
                      const CaptureDecodeSummary& s) {
    using nlohmann::json;
    timings["dark"] = s.seconds.dark;
    timings["preprocess"] = s.seconds.preprocess;
    timings["period_check"] = s.seconds.period_check;
    timings["crop"] = s.seconds.crop;
    timings["decode"] = s.seconds.decode;
    timings["fft_planning"] = s.seconds.fft_planning;
    stats["period_check"] = period_check_json(s.period);
    stats["window"] = {{"x", s.window.col},
                       {"y", s.window.row},
                       {"cols", s.window.cols},
                       {"rows", s.window.rows},
                       {"mode", r.crop}};
    const NormalizeMode normalize = parse_normalize_mode(r.normalize, "--normalize");
    json norm = {{"mode", normalize_mode_name(normalize)}};
    if (normalize == NormalizeMode::kL2) {
        norm["capture_l2_norms"] = s.capture_l2_norms;
        norm["psf_l2_norms"] = s.psf_l2_norms;
    } else {
        norm["psf_sums"] = s.psf_sums;
    }
    json backgrounds = json::array();
    if (s.background) backgrounds.push_back(*s.background);
    stats["preprocess"] = {{"background",
                            {{"mode", background_mode_name(parse_background(r.background).mode)},
                             {"values", backgrounds}}},
                           {"downsample_rounds", r.downsample},
                           {"normalize", norm},
                           {"decoded_rows", s.decoded_rows},
                           {"decoded_cols", s.decoded_cols}};
    stats["method"] = r.method;
    stats["precision"] =
        precision_name(s.single_precision ? Precision::kSingle : Precision::kDouble);
    stats["fft_threads"] = s.fft_threads;
    json channels = json::array(), per_channel = json::array(), history_seconds = json::array();
    for (std::size_t ch = 0; ch < s.channels.size(); ++ch) {
        const DecodeResult& d = s.channels[ch];
        json history = json::array(), hs = json::array();
        for (const auto& h : d.history) {
            history.push_back(
                {{"iteration", h.iteration}, {"objective", h.objective}, {"residual", h.residual}});
            hs.push_back(h.seconds);
        }
        channels.push_back({{"channel", ch},
                            {"iterations", d.iterations},
                            {"objective", d.objective},
                            {"residual", d.residual},
                            {"converged", d.converged},
                            {"constraint_met", d.constraint_met},
                            {"interrupted", d.interrupted},
                            {"history", history}});
        per_channel.push_back(d.seconds);
        history_seconds.push_back(hs);
    }
    stats["channels"] = channels;
    if (s.interrupted) stats["interrupted"] = true;
    timings["decode_channels"] = per_channel;
    timings["history_seconds"] = history_seconds;
}

void check_output_range(const Image& estimate, OutputKind kind) {
    if (kind == OutputKind::kPng) return;
    double peak = 0.0;
    for (const Plane& p : estimate.channels) peak = std::max(peak, p.abs().maxCoeff());
    if (peak > 3.4028234663852886e38) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3g", peak);
        throw invalid_field("-o", buf,
                            "the estimate exceeds the float32 range of .tif/.npy output "
                            "(|x| <= 3.4e38); scale the capture down or write a .png");
    }
}

Background parse_background(const std::string& s) {
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

nlohmann::json config_json(const DecodeRequest& r) {
    auto opt = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json();
    };
    auto path = [](const std::string& p) {
        return p.empty() ? nlohmann::json() : nlohmann::json(p);
    };
    return {{"format", "pinmask-decode-config"},
            {"version", 1},
            {"capture", r.capture},
            {"mask", path(r.mask)},
            {"psf", path(r.psf)},
            {"dark", path(r.dark)},
            {"crop", r.crop},
            {"method", r.method},
            {"model", r.model},
            {"nsr", r.nsr},
            {"lambda", r.lambda},
            {"regulariser", r.regulariser},
            {"eps", opt(r.eps)},
            {"noise_sigma", opt(r.noise_sigma)},
            {"nonnegative", r.nonnegative},
            {"iterations", r.iterations},
            {"tolerance", r.tolerance},
            {"downsample", r.downsample},
            {"background", r.background},
            {"normalize", r.normalize},
            {"output", r.output},
            {"bits", r.bits},
            {"scale", r.scale},
            {"stats", path(r.stats)},
            {"precision", r.precision},
            {"threads", r.threads == 0 ? nlohmann::json("all") : nlohmann::json(r.threads)},
            {"orientation", "capture pixel grid, not flipped or mirrored"}};
}

OutputKind output_kind(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png") return OutputKind::kPng;
    if (ext == ".tif" || ext == ".tiff") return OutputKind::kTiff;
    if (ext == ".npy") return OutputKind::kNpy;
    throw invalid_field("-o", path.string(),
                        "the extension must be .png (scaled 8/16-bit), .tif/.tiff or .npy "
                        "(raw float32)");
}

const char* output_kind_name(OutputKind kind) {
    switch (kind) {
        case OutputKind::kPng:
            return "png";
        case OutputKind::kTiff:
            return "tiff-float32";
        case OutputKind::kNpy:
            return "npy-float32";
    }
    return "?";
}

ScaledImage scale_for_png(const Image& estimate, std::optional<double> scale) {
    ScaledImage s;
    s.image = estimate;
    for (Plane& p : s.image.channels) {
        p = p.max(0.0);
        if (p.size() > 0) s.max_value = std::max(s.max_value, p.maxCoeff());
    }
    s.factor = scale ? *scale : (s.max_value > 0.0 ? 1.0 / s.max_value : 0.0);
    for (Plane& p : s.image.channels) p = (p * s.factor).min(1.0);
    return s;
}

void write_output_image(const std::filesystem::path& path, const Image& image, OutputKind kind,
                        int bits) {
    switch (kind) {
        case OutputKind::kPng:
            write_png(path, image, bits);
            return;
        case OutputKind::kTiff:
            write_tiff(path, image, SampleFormat::kFloat32);
            return;
        case OutputKind::kNpy:
            write_npy(path, image, SampleFormat::kFloat32);
            return;
    }
}

nlohmann::json period_check_json(const PeriodCheck& check) {
    return {{"checked", check.checked()},
            {"matches", check.matches()},
            {"tolerance_px", check.tolerance_px},
            {"rows", axis_json(check.rows)},
            {"cols", axis_json(check.cols)}};
}

std::string period_warning(const PeriodCheck& check) {
    std::string out;
    const std::pair<const AxisPeriodCheck*, const char*> axes[] = {{&check.rows, "rows (y)"},
                                                                   {&check.cols, "columns (x)"}};
    for (const auto& [a, name] : axes) {
        if (!a->checked || a->matches) continue;
        if (a->found) {
            out += "the capture repeats every " + fixed(a->measured_px, 2) + " px along the " +
                   name + " but the PSF period is " + std::to_string(a->expected_px) +
                   " px (tolerance " + fixed(check.tolerance_px, 2) +
                   " px): the PSF does not match this capture (object distance, pixel pitch or "
                   "sensor distance differ from the mask file?)\n";
        } else {
            out += std::string("no repeat found along the ") + name + " (expected every " +
                   std::to_string(a->expected_px) +
                   " px): the capture may not come from this mask, or the scene is too dark\n";
        }
    }
    return out;
}

std::string period_skip_note(const PeriodCheck& check) {
    std::string out;
    if (!check.rows.checked)
        out += "period check skipped along the rows: " + check.rows.skip_reason + "\n";
    if (!check.cols.checked)
        out += "period check skipped along the columns: " + check.cols.skip_reason + "\n";
    return out;
}

}  // namespace pinmask::cli
