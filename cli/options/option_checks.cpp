#include "cli/options/option_checks.hpp"

#include <charconv>
#include <cstdint>
#include <string>
#include <system_error>

namespace pinmask::cli {

void refuse_negative_unsigned(CLI::App& app) {
    for (CLI::Option* opt : app.get_options()) {
        if (opt->get_type_name() != "UINT") continue;
        opt->check(CLI::Validator(
            [](std::string& value) -> std::string {
                const auto first = value.find_first_not_of(" \t");
                if (first != std::string::npos && value[first] == '-') {
                    return "must be >= 0: an unsigned value (a seed or a count), " + value +
                           " would wrap around to a huge number";
                }
                // strtoull saturates silently: 2^64 would become 2^64 - 1.
                std::uint64_t parsed = 0;
                const char* end = value.data() + value.size();
                const auto [ptr, ec] = std::from_chars(
                    value.data() + (first == std::string::npos ? 0 : first), end, parsed);
                if (ec == std::errc::result_out_of_range) {
                    return "must be at most 18446744073709551615 (2^64 - 1, the largest unsigned "
                           "64-bit value), " +
                           value + " would be cut to it";
                }
                return {};
            },
            ""));
    }
    for (CLI::App* sub : app.get_subcommands({})) refuse_negative_unsigned(*sub);
}

}  // namespace pinmask::cli
