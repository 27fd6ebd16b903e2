#include "cli/options/length_option.hpp"

#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "core/units.hpp"

namespace pinmask::cli {

CLI::Option* length_in_metres(CLI::Option* opt) {
    const std::string flag = opt->get_name();
    opt->transform(CLI::Validator(
        [flag](std::string& value) -> std::string {
            try {
                const double m = parse_length_m(value, flag);
                char text[32];
                std::snprintf(text, sizeof text, "%.17g", m);
                value = text;
                return {};
            } catch (const InvalidInput& e) {
                // CLI11 puts the flag in front of the message already.
                std::string why = e.what();
                const std::string prefix = flag + " = ";
                if (why.rfind(prefix, 0) == 0) why.erase(0, prefix.size());
                return why;
            }
        },
        "LENGTH"));
    return opt;
}

}  // namespace pinmask::cli
