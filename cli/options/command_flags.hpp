// A message as one command says it: every field reference spelled as its flag
// (cli/options/flag_names), except a flag the command does not have, which is named with the
// commands that do, so no message tells a user to pass a flag the command refuses.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

namespace pinmask::cli {

// A field whose flag `command` has is spelled as the flag; one whose flag it lacks as
// "--flag (a flag of pinmask A, B, not of C)", naming the sibling commands that have it.
std::string spell_flags(std::string_view message, const CLI::App& command);

}  // namespace pinmask::cli
