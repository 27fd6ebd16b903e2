#include "cli/outputs/decode_output.hpp"

#include <cmath>

#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "core/units/number_format.hpp"
#include "core/units/units.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/decode_modes.hpp"
#include "io/json_strict.hpp"

namespace pinmask::cli {
namespace {

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
        j["early_exit"] = a.early_exit;
        j["within_tolerance"] = a.within_tolerance;
        if (!a.early_exit) {
            j["high_pass_px"] = a.high_pass_px;
            j["uncertainty_px"] = nlohmann::json(io::json_strict::finite_or_null(a.uncertainty_px));
            j["significance"] = nlohmann::json(io::json_strict::finite_or_null(a.significance));
        }
    }
    j["matches"] = a.matches;
    return j;
}

}  // namespace

void add_summary_json(nlohmann::json& stats, nlohmann::json& timings, const DecodeCommand& r,
                      const CaptureDecodeSummary& s) {
    using nlohmann::json;
    stats["chosen"] = chosen_json(s.chosen);
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
    const NormalizeMode normalize = r.request.normalize;
    json norm = {{"mode", normalize_mode_name(normalize)}};
    if (normalize == NormalizeMode::kL2) {
        norm["capture_l2_norms"] = s.capture_l2_norms;
        norm["psf_l2_norms"] = s.psf_l2_norms;
    } else {
        norm["psf_sums"] = s.psf_sums;
    }
    json backgrounds = json::array();
    if (s.background) backgrounds.push_back(*s.background);
    stats["preprocess"] = {
        {"background",
         {{"mode", background_mode_name(r.request.background.mode)}, {"values", backgrounds}}},
        {"downsample_rounds", r.request.downsample},
        {"normalize", norm},
        {"bayer", r.bayer},
        {"decoded_rows", s.decoded_rows},
        {"decoded_cols", s.decoded_cols}};
    stats["method"] = decode_method_name(s.method);  // given, or chosen (auto: "chosen")
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
        if (d.auto_weight) {
            channels.back()["auto_weight"] = {{"weight", d.auto_weight->weight},
                                              {"noise_sigma", d.auto_weight->noise_sigma},
                                              {"scene_spectrum_exponent", d.auto_weight->alpha}};
        }
        per_channel.push_back(d.seconds);
        history_seconds.push_back(hs);
    }
    stats["channels"] = channels;
    if (!s.warnings.empty()) {
        json warnings = json::array();
        for (const std::string& w : s.warnings) warnings.push_back(spell_flags(w));
        stats["warnings"] = warnings;
    }
    if (s.interrupted) stats["interrupted"] = true;
    timings["decode_channels"] = per_channel;
    timings["history_seconds"] = history_seconds;
}

nlohmann::json chosen_json(const std::vector<ChosenSetting>& chosen) {
    nlohmann::json out = nlohmann::json::object();
    for (const ChosenSetting& c : chosen)
        out[c.name] = {{"value", c.value}, {"reason", spell_flags(c.reason)}};
    return out;
}

nlohmann::json config_json(const DecodeCommand& c) {
    const DecodeRequest& r = c.request;
    auto opt = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json();
    };
    auto path = [](const std::string& p) {
        return p.empty() ? nlohmann::json() : nlohmann::json(p);
    };
    return {{"format", "pinmask-decode-config"},
            {"version", 1},
            {"capture", c.capture},
            {"mask", path(c.mask)},
            {"psf", path(c.psf)},
            {"dark", path(c.dark)},
            {"crop", c.crop},
            {"method", c.method},
            {"model", c.model},
            {"nsr", r.nsr_auto ? nlohmann::json("auto") : nlohmann::json(r.nsr)},
            {"nsr_map", path(c.nsr_map)},
            {"lambda", r.lambda_auto ? nlohmann::json("auto") : nlohmann::json(r.lambda)},
            {"regulariser", c.regulariser},
            {"eps", opt(r.eps)},
            {"noise_sigma", opt(r.noise_sigma)},
            {"nonnegative", r.nonnegative},
            {"iterations", r.iterations},
            {"tolerance", r.tolerance},
            {"downsample", r.downsample},
            {"background", c.background},
            {"normalize", c.normalize},
            {"bayer", c.bayer},
            {"output", c.output},
            {"bits", c.bits},
            {"scale", c.scale},
            {"stats", path(c.stats)},
            {"precision", c.precision},
            {"threads", r.threads == 0 ? nlohmann::json("all") : nlohmann::json(r.threads)},
            {"orientation", "capture pixel grid, not flipped or mirrored"}};
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
            out += "the capture repeats every " + format_cell(a->measured_px, "%.2f") +
                   " px along the " + name + " but the PSF period is " +
                   std::to_string(a->expected_px) + " px (tolerance " +
                   format_cell(check.tolerance_px, "%.2f") + " px" +
                   (a->early_exit || !std::isfinite(a->significance)
                        ? std::string()
                        : ", significance t = " + format_cell(a->significance, "%.1f")) +
                   "): the PSF does not match this capture (object distance, pixel pitch or "
                   "sensor distance differ from the mask file?)\n";
        } else {
            out += std::string("no repeat found along the ") + name + " (expected every " +
                   std::to_string(a->expected_px) +
                   " px): the capture may not come from this mask, or the scene is too dark\n";
        }
    }
    return out;
}

std::string period_summary(const PeriodCheck& check) {
    if (!check.checked()) {
        const bool none = !check.rows.found && !check.cols.found &&
                          (check.rows.skip_reason.find("no repeat") != std::string::npos ||
                           check.cols.skip_reason.find("no repeat") != std::string::npos);
        return none ? "not checked (no measurable repeat)" : "not checked (fewer than two periods)";
    }
    if (!check.matches()) return "MISMATCH (see warning)";
    for (const AxisPeriodCheck* a : {&check.rows, &check.cols}) {
        if (a->checked && !a->within_tolerance)
            return "consistent with the PSF within the measurement's uncertainty (a weak or broad "
                   "repeat; --explain gives the figures)";
    }
    return "matches the PSF";
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
