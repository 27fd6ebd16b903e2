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

void refuse_non_decimal_integers(CLI::App& app) {
    for (CLI::Option* opt : app.get_options()) {
        const std::string type = opt->get_type_name();
        if (type != "INT" && type != "UINT") continue;
        opt->check(CLI::Validator(
            [](std::string& value) -> std::string {
                const auto first = value.find_first_not_of(" \t");
                if (first == std::string::npos) return {};  // CLI11 refuses it as empty
                std::size_t i = first;
                if (value[i] == '+' || value[i] == '-') ++i;
                const std::size_t digits = i;
                while (i < value.size() && value[i] >= '0' && value[i] <= '9') ++i;
                const bool decimal =
                    i > digits && value.find_first_not_of(" \t", i) == std::string::npos;
                if (!decimal) {
                    const std::string body = value.substr(digits);
                    if (body.size() > 1 && body[0] == '0' &&
                        std::string("xXoObB").find(body[1]) != std::string::npos)
                        return "must be a whole number in decimal digits: " + value +
                               " would be read in another base (0x hexadecimal, 0o octal, 0b "
                               "binary)";
                    return {};  // not a number at all: CLI11 refuses it in its words
                }
                // A leading zero makes CLI11 read the rest as octal ("010" is 8).
                if (i - digits > 1 && value[digits] == '0')
                    return "must be a whole number in decimal digits without a leading zero: " +
                           value + " would be read as octal";
                return {};
            },
            ""));
    }
    for (CLI::App* sub : app.get_subcommands({})) refuse_non_decimal_integers(*sub);
}

}  // namespace pinmask::cli
