#include "cli/options/number_lists.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "cli/options/noise_options.hpp"
#include "core/errors/error.hpp"
#include "core/units/units.hpp"

namespace pinmask::cli {

std::vector<std::string> item_list(const std::string& text, const std::string& flag) {
    return split_list(text, flag, std::numeric_limits<std::size_t>::max());
}

std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ",") + item;
    return out;
}

std::string joined(const std::vector<double>& numbers) {
    std::vector<std::string> items;
    for (const double v : numbers) {
        std::ostringstream s;
        s.precision(17);
        s << v;
        items.push_back(s.str());
    }
    return joined(items);
}

std::vector<double> number_list(const std::string& text, const std::string& flag) {
    std::vector<double> out;
    for (const auto& s : item_list(text, flag)) out.push_back(parse_number(s, flag));
    return out;
}

std::vector<int> count_list(const std::string& text, const std::string& flag) {
    std::vector<int> out;
    for (const auto& s : item_list(text, flag)) {
        const double v = parse_number(s, flag);
        if (v != std::floor(v) || v < 1 || v > 1e6) {
            throw invalid_field(flag, s, "must be an integer in 1..1000000");
        }
        out.push_back(static_cast<int>(v));
    }
    return out;
}

}  // namespace pinmask::cli
