// The words for each figure's name (the names are io/metrics_json.hpp's: one name per figure in
// score, search, compare, the report, JSON and Python), for the tables and reports that show
// them.
#pragma once

#include <string>

namespace pinmask {

// "analytic MMSE PSNR", "analytic Wiener PSNR", "simulated Wiener PSNR", ...; the name itself
// for a name it does not know.
std::string figure_words(const std::string& name);

}  // namespace pinmask
