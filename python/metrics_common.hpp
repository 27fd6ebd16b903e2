// The compare settings and metric row shared by bind_metrics (metrics) and bind_compare.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "optimize/compare.hpp"
#include "python/common.hpp"

namespace pinmask::python {

// `pinmask compare`'s make_options with the same flags (same checks and messages): Gaussian
// noise at snr_db, the natural prior of prior_scenes textures, every metric (tv included).
CompareSettings compare_settings(double snr_db, const std::vector<std::string>& scenes,
                                 int prior_scenes, const std::string& nsr,
                                 const std::string& tv_lambda, int tv_iterations,
                                 std::uint64_t seed);

// A metric row as a dict with the keys of `pinmask compare --json` (infinities as float inf).
py::dict row_dict(const CompareRow& row);

}  // namespace pinmask::python
