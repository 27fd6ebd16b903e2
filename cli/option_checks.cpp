#include "cli/option_checks.hpp"

#include <string>

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
                return {};
            },
            "UINT >= 0"));
    }
    for (CLI::App* sub : app.get_subcommands({})) refuse_negative_unsigned(*sub);
}

}  // namespace pinmask::cli
