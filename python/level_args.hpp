// The noise levels and scene prior arguments of metrics(), compare() and search(), as
// `pinmask score/compare/search` take them: snr_db (Gaussian, dB) or photons (the photon model,
// electrons per pixel per pinhole) with the sensor stages, each a number or a list of numbers;
// prior 'natural' | 'text' | 'stars' or image files (a list of paths or one comma-separated
// string) with prior_scenes sample scenes. Checks and messages are the library's
// (optimize/metrics/noise_levels, optimize/metrics/mask_metrics parse_prior_spec), naming the CLI's
// flags.
#pragma once

#include <string>
#include <vector>

#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/noise_levels.hpp"
#include "python/common.hpp"

namespace pinmask::python {

// The levels: photons when not None (snr_db must then be None: "`snr_db` ... cannot be combined
// with `photons`"), else snr_db (None: `default_snr_db`). `text` gets the levels in words.
std::vector<NoiseLevel> noise_levels_arg(const py::object& snr_db, const py::object& photons,
                                         const SensorSettings& sensor,
                                         const std::vector<double>& default_snr_db,
                                         std::string* text = nullptr);

// The prior of the analytic error.
PriorSpec prior_arg(const py::object& prior, int prior_scenes);

}  // namespace pinmask::python
