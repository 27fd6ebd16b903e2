// A length flag stored as metres: the value may carry a unit as every other length flag does
// ("0.4m", "400mm", "2"; a plain number is metres, core/units), and is converted before CLI11
// stores it, so the option's variable stays a double and a config file's plain number still
// merges into it.
#pragma once

#include <CLI/CLI.hpp>

namespace pinmask::cli {

// Adds the conversion to `opt` (a double option) and returns it. A value that is not a length
// is refused naming the flag, as CLI11 refuses any bad value (exit 2).
CLI::Option* length_in_metres(CLI::Option* opt);

}  // namespace pinmask::cli
