// The text spellings of the metric settings that score, compare, search and the Python module
// share: the Wiener filter of the analytic error, a simulated decoder's weight, the scenes and
// the decoder settings of score and compare. Errors name the settings' fields
// (core/errors/field_names.hpp), which each face spells as its flag or keyword.
#pragma once

#include <string>
#include <vector>

#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {

// "optimal" (per-frequency Wiener filter), "tuned" (deconvwnr's NSR tuned per pattern) or
// "nsr:VALUE" (deconvwnr's fixed NSR, > 0); InvalidInput naming `filter` otherwise.
WienerFilterSpec parse_wiener_filter(const std::string& text);

// The search's `filter`: "auto" is "tuned" under the photon model (what the simulated and the
// decoded Wiener do; the optimal filter's figure does not predict them there) and
// "optimal" under a Gaussian SNR (kept so masks searched before stay reproducible); anything
// else as parse_wiener_filter.
WienerFilterSpec parse_search_filter(const std::string& text, const NoiseModel& noise);

// A simulated decoder's weight (Wiener NSR, TV lambda): "tuned" or a number > 0; InvalidInput
// naming `field` otherwise.
WeightChoice parse_weight_choice(const std::string& text, const std::string& field);

// The `scenes` names (built-in names or image files, scene_from_name) as scene specs; the natural
// scene is pinned to texture seed 0, so every noise seed and every mask sees the same picture.
std::vector<SceneSpec> scene_specs_from_names(const std::vector<std::string>& names);

// The simulated decoders' NSR, TV lambda and TV iterations into sim (InvalidInput naming
// `wiener_nsr`, `tv_lambda` or `tv_iterations`).
void set_decoder_settings(SimulatedMetricsOptions& sim, const std::string& nsr,
                          const std::string& tv_lambda, int tv_iterations);

// The metric groups of score's selection ("sidelobes", "spectrum", "analytic", "wiener", "tv",
// "depth"):
// each named group on, the others off. InvalidInput naming `metrics` for an unknown or empty
// name, or an empty list.
void select_metrics(MaskMetricsOptions& m, const std::vector<std::string>& names);

// The names select_metrics accepts, in the order score lists them.
const std::vector<std::string>& metric_group_names();

}  // namespace pinmask
