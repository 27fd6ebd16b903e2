// Checks applied to every option of every subcommand at once, so no command can forget them.
#pragma once

#include <CLI/CLI.hpp>

namespace pinmask::cli {

// Every option stored in an unsigned integer (CLI11 type name "UINT": seeds, counts) refuses a
// value with a minus sign: strtoull would wrap "-1" to 2^64 - 1. The message names the option
// and the rule. Applied recursively to the subcommands.
void refuse_negative_unsigned(CLI::App& app);

}  // namespace pinmask::cli
