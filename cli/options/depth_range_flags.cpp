#include "cli/options/depth_range_flags.hpp"

#include <cstdio>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"

namespace pinmask::cli {
namespace {

// Converts the option's text to metres (%.17g) before CLI11 stores it; a value that is not a
// length is refused naming the flag, as CLI11 refuses any bad value (exit 2).
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

}  // namespace

void add_depth_range_flags(CLI::App& cmd, double& from_m, double& to_m, const std::string& with) {
    length_in_metres(cmd.add_option(
        "--depth-from", from_m,
        "With " + with +
            ": the nearest object distance of the depth range (length, e.g. 0.4m; > f'; default "
            "with --depth-to unset: the working distance / 2)"));
    length_in_metres(cmd.add_option("--depth-to", to_m,
                                    "With " + with +
                                        ": the farthest object distance (length, e.g. 2m; >= "
                                        "--depth-from; default: twice the working distance)"));
}

DepthRange depth_range_of(const CLI::App& cmd, double from_m, double to_m, bool depth_on,
                          const std::string& add) {
    if (!depth_on && (cmd.get_option("--depth-from")->count() > 0 ||
                      cmd.get_option("--depth-to")->count() > 0)) {
        throw InvalidInput("--depth-from/--depth-to: " + add +
                           " (the range is the depth figure's)");
    }
    DepthRange r;
    r.from_m = from_m;
    r.to_m = to_m;
    return r;
}

}  // namespace pinmask::cli
