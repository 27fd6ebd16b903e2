#include "cli/decode_output.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/units.hpp"

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
        if (x == static_cast<int>(x) && y == static_cast<int>(y))
            return {CropMode::kCorner, static_cast<int>(y), static_cast<int>(x)};
    }
    throw invalid_field("--crop", s, "must be center, none or X,Y (integer pixel corner)");
}

static DecodeMethod parse_method(const std::string& m) {
    if (m == "wiener") return DecodeMethod::kWiener;
    if (m == "tikhonov") return DecodeMethod::kTikhonov;
    if (m == "tv") return DecodeMethod::kTv;
    if (m == "tvqc") return DecodeMethod::kTvqc;
    if (m == "rl") return DecodeMethod::kRichardsonLucy;
    throw invalid_field("--method", m, "must be wiener, tikhonov, tv, tvqc or rl");
}

DecodeOptions decode_options(const DecodeRequest& r) {
    DecodeOptions d;
    d.method = parse_method(r.method);
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

Background parse_background(const std::string& s) {
    if (s == "none" || s == "corner") return {s, 0.0};
    return {"value", parse_number(s, "--background")};
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
