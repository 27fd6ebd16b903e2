// Shared by score, compare and search: the flags of the one metric set
// (optimize/metrics/mask_metrics) and its JSON rendering, so every command names and prints the
// same numbers the same way.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/metrics_json.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/simulated_metrics.hpp"

namespace pinmask::cli {

// The filter, weight and decoder spellings (optimize/metrics/metric_spellings.hpp), under their old
// names.
using pinmask::parse_weight_choice;
using pinmask::parse_wiener_filter;
using pinmask::set_decoder_settings;

// --prior and --prior-scenes.
struct PriorFlags {
    std::string prior = "natural";
    int count = kDefaultPriorScenes;
};
void add_prior_flags(CLI::App& cmd, PriorFlags& flags);
PriorSpec prior_spec(const PriorFlags& flags);

// --scenes (comma-separated names or image files) as scene specs (scene_specs_from_names: the
// natural scene pinned to texture seed 0).
std::vector<SceneSpec> scene_specs(const std::string& scenes);

// The metrics as score's JSON keys (io/metrics_json, shared with the Python module).
using io::metrics_json;

// score's text table of JSON rows (one per mask), with spectral-zero warnings and a legend.
std::string metrics_table_text(const std::vector<nlohmann::ordered_json>& rows,
                               const MaskMetricsOptions& m);

}  // namespace pinmask::cli
