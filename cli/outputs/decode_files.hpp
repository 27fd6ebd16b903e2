// What one decode writes and prints, for `pinmask decode` and each capture of `decode --batch`:
// the estimate at OUT (a PNG scaled by --scale, else by its largest value; .tif/.npy the raw
// float32 estimate) and OUT.config.json staged together, the summary's warnings on stderr and
// its table on stdout.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "cli/options/decode_flags.hpp"
#include "core/files/atomic_file.hpp"
#include "core/image/image.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/capture/estimate_output.hpp"

namespace pinmask::cli {

struct StagedDecode {
    nlohmann::json output;  // the stats' "output": path, format, config (PNG: bits, scaling...)
    nlohmann::json config;  // OUT.config.json (config_json with "chosen")
};

// Stages the estimate at r.output as `kind` and OUT.config.json (`chosen`: the stats' "chosen",
// add_summary_json) into `files`.
StagedDecode stage_decode_files(StagedFiles& files, const DecodeCommand& r, const Image& estimate,
                                OutputKind kind, std::optional<double> scale,
                                const nlohmann::json& chosen);

// A PNG output that came out black (no positive value, or every pixel rounds to 0 at --scale):
// a warning on stderr. Nothing for other outputs.
void warn_black_png(const StagedDecode& staged, int bits);

// The summary's problems on stderr, each "pinmask: warning: ...": the period check's lines, the
// pipeline's warnings (in the command's flags; a method or weight the input makes poor, not
// printed under --quiet, `quiet`: the stats keep them), an interrupted solve, TVQC's constraint
// not met.
void print_decode_warnings(const CaptureDecodeSummary& sum, bool quiet);

// The summary table on stdout: method, model, precision, window, per channel its iterations,
// residual, objective and time, the period verdict and the files written.
void print_decode_summary(const DecodeCommand& r, const CaptureDecodeSummary& sum);

}  // namespace pinmask::cli
