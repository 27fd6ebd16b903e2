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

// The inverse, for a flag's default shown in --help: items joined by commas, numbers in their
// shortest round-trip form (20, 0.001).
std::string joined(const std::vector<std::string>& items);
std::string joined(const std::vector<double>& numbers);

// Whole numbers in 1..1000000.
std::vector<int> count_list(const std::string& text, const std::string& flag);

}  // namespace pinmask::cli
