// Comma-separated items and numbers of a flag ("1e-4,3e-4,1e-3", "1,3,10"), as
// cli/options/noise_options split_list splits them, with no cap on their count (InvalidInput naming
// the flag).
#pragma once

#include <string>
#include <vector>

namespace pinmask::cli {

// The items themselves, none empty.
std::vector<std::string> item_list(const std::string& text, const std::string& flag);

std::vector<double> number_list(const std::string& text, const std::string& flag);

// Whole numbers in 1..1000000.
std::vector<int> count_list(const std::string& text, const std::string& flag);

}  // namespace pinmask::cli
