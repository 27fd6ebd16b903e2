// Checks applied to every option of every subcommand at once, so no command can forget them.
#pragma once

#include <CLI/CLI.hpp>

namespace pinmask::cli {

// Every option stored in an unsigned integer (CLI11 type name "UINT": seeds, counts) refuses a
// value with a minus sign: strtoull would wrap "-1" to 2^64 - 1. The message names the option
// and the rule. Applied recursively to the subcommands.
void refuse_negative_unsigned(CLI::App& app);

// Every option stored in an integer (CLI11 type names "INT" and "UINT": counts, seeds, layers,
// sides) takes decimal digits only, with an optional sign: CLI11 reads "0x8" as hexadecimal 8
// and "010" as octal 8, so `--layer 010` wrote layer 8 without a word. Such a value is refused
// naming the option and what it would have been read as. Applied recursively to the subcommands.
void refuse_non_decimal_integers(CLI::App& app);

}  // namespace pinmask::cli
