// The compare settings and metric row shared by bind_metrics (metrics) and bind_compare.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "optimize/metrics/compare.hpp"
#include "python/common.hpp"

namespace pinmask::python {

// `pinmask compare`'s make_options with the same flags (same checks and messages): the noise
// levels and prior of python/level_args, every metric (tv included).
CompareSettings compare_settings(std::vector<NoiseLevel> levels, PriorSpec prior,
                                 const std::vector<std::string>& scenes, const std::string& nsr,
                                 const std::string& tv_lambda, int tv_iterations,
                                 std::uint64_t seed);

// A metric row as a dict with the keys of `pinmask compare --json` (infinities as float inf),
// every noise level under score's keys (analytic_wiener_psnr_db_snr30, wiener_psnr_db_ph100, ...).
py::dict row_dict(const CompareRow& row);

}  // namespace pinmask::python
