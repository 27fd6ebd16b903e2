// Output side of `pinmask decode`: the resolved configuration and the stats as JSON, the JSON
// of the period check, and the warning text for a period mismatch. The command's settings are
// cli/options/decode_flags.hpp's; the output image is the decode library's
// (decode/capture/estimate_output.hpp).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/options/decode_flags.hpp"
#include "core/image/image.hpp"
#include "decode/capture/capture.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/capture/decode_request.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/capture/estimate_output.hpp"
#include "decode/capture/period.hpp"

namespace pinmask::cli {

// The request's options (decode/capture/decode_request.hpp) and the estimate's output file
// (decode/capture/estimate_output.hpp), under their old names.
using pinmask::capture_decode_options;
using pinmask::check_output_range;
using pinmask::output_kind;
using pinmask::output_kind_name;
using pinmask::OutputKind;
using pinmask::scale_for_png;
using pinmask::ScaledImage;
using pinmask::write_output_image;

// Adds the pipeline's results to the stats JSON and its timings to `timings`. Everything
// outside "timings_s" is deterministic (same inputs and options: the same bytes); all
// wall-clock figures (per stage, per channel, per iteration) go to `timings`.
void add_summary_json(nlohmann::json& stats, nlohmann::json& timings, const DecodeCommand& command,
                      const CaptureDecodeSummary& summary);

// The settings read from the data (CaptureDecodeSummary::chosen): {name: {"value", "reason"}},
// reasons spelt with the command's flags. The stats carry it as "chosen" (add_summary_json), and
// so does OUT.config.json.
nlohmann::json chosen_json(const std::vector<ChosenSetting>& chosen);

// The resolved configuration (every option with its value, defaults filled in), as written to
// OUT.config.json and into the stats. The text flags appear as given.
nlohmann::json config_json(const DecodeCommand& command);

// The period check as JSON (per-axis figures, skip reasons, tolerance, verdict).
nlohmann::json period_check_json(const PeriodCheck& check);

// One line per problem for stderr: a mismatch or a missing repeat, with measured and expected
// figures; empty when every checked axis matched (or nothing was checked).
std::string period_warning(const PeriodCheck& check);

// Why the check was skipped, axis by axis; empty when both axes were checked.
std::string period_skip_note(const PeriodCheck& check);
// The summary's one-line verdict: matches, consistent within the uncertainty, MISMATCH, or not
// checked (and why).
std::string period_summary(const PeriodCheck& check);

}  // namespace pinmask::cli
