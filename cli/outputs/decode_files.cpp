#include "cli/outputs/decode_files.hpp"

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "cli/options/flag_names.hpp"
#include "cli/outputs/decode_output.hpp"
#include "decode/solvers/decode_method.hpp"

namespace pinmask::cli {

namespace fs = std::filesystem;

StagedDecode stage_decode_files(StagedFiles& files, const DecodeCommand& r, const Image& estimate,
                                OutputKind kind, std::optional<double> scale,
                                const nlohmann::json& chosen) {
    StagedDecode s;
    s.output = {{"path", r.output},
                {"format", output_kind_name(kind)},
                {"config", r.output + ".config.json"}};
    if (kind == OutputKind::kPng) {
        const ScaledImage png = scale_for_png(estimate, scale);
        files.stage(r.output,
                    [&](const fs::path& tmp) { write_output_image(tmp, png.image, kind, r.bits); });
        s.output["bits"] = r.bits;
        s.output["scaling"] = scale ? "factor" : "max";
        s.output["scale_factor"] = png.factor;
        s.output["max_value"] = png.max_value;
    } else {
        files.stage(r.output,
                    [&](const fs::path& tmp) { write_output_image(tmp, estimate, kind, r.bits); });
    }
    s.config = config_json(r);
    s.config["chosen"] = chosen;  // add_summary_json: what auto chose
    files.stage_bytes(r.output + ".config.json", s.config.dump(2) + "\n");
    return s;
}

void warn_black_png(const StagedDecode& staged, int bits) {
    if (!staged.output.contains("max_value")) return;  // not a PNG
    const double max_value = staged.output["max_value"], factor = staged.output["scale_factor"];
    if (max_value <= 0.0)
        std::cerr << "pinmask: warning: the estimate has no positive value; the PNG is black\n";
    else if (max_value * factor * double((1 << bits) - 1) < 0.5)
        std::cerr << "pinmask: warning: at --scale " << factor
                  << " every pixel rounds to 0: the PNG is black (the estimate's largest value is "
                  << max_value << ")\n";
}

void print_decode_warnings(const CaptureDecodeSummary& sum, bool quiet) {
    std::istringstream warnings(period_warning(sum.period));
    for (std::string line; std::getline(warnings, line);)
        std::cerr << "pinmask: warning: " << line << "\n";
    if (!quiet)
        for (const std::string& w : sum.warnings)
            std::cerr << "pinmask: warning: " << spell_flags(w) << "\n";
    if (sum.interrupted) {
        std::cerr << "pinmask: interrupted: writing the estimate after "
                  << sum.channels.front().iterations << " iterations (not converged)\n";
    }
    if (!sum.constraint_met) {
        std::cerr << "pinmask: warning: tvqc did not meet its constraint ||Ax - p||_2 <= eps "
                     "(see \"constraint_met\" and \"residual\" in the stats); the estimate is "
                     "written but is not a TVQC solution\n";
    }
}

void print_decode_summary(const DecodeCommand& r, const CaptureDecodeSummary& sum) {
    std::cout << "decode " << r.capture << " -> " << r.output << "\n"
              << "  method   " << decode_method_name(sum.method)
              << (r.request.method_auto ? " (auto; " : " (") << conv_model_name(sum.model)
              << " model, " << (sum.single_precision ? "single" : "double") << " precision)\n"
              << "  window   " << sum.window.cols << " x " << sum.window.rows
              << " at x=" << sum.window.col << ", y=" << sum.window.row << "\n";
    for (std::size_t ch = 0; ch < sum.channels.size(); ++ch) {
        const DecodeResult& d = sum.channels[ch];
        std::cout << "  channel " << ch << "  iterations " << d.iterations << "  residual "
                  << d.residual << "  objective " << d.objective << "  " << d.seconds << " s"
                  << (d.interrupted ? "  (interrupted)" : "")
                  << (d.constraint_met ? "" : "  (constraint NOT met)") << "\n";
    }
    std::cout << "  period   " << period_summary(sum.period) << "\n  wrote    " << r.output << ", "
              << r.output << ".config.json" << (r.stats.empty() ? "" : ", " + r.stats) << "\n";
}

}  // namespace pinmask::cli
