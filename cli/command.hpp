// Subcommand registry: each cli/cmd_*.cpp registers one subcommand with a static Registration;
// main() only wires them. A subcommand's callback throws pinmask errors; main maps them to exit
// codes (InvalidInput -> 2, other errors -> 1). Commands that finish with a verdict other than
// "ok" (e.g. `check` found violations) call set_exit_code().
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace pinmask::cli {

struct Registration {
    // order sorts the subcommands in --help; setup adds the subcommand to `parent_app`, which is
    // the top-level app, or the subcommand named `parent` (e.g. "bench" for `pinmask bench X`).
    Registration(int order, std::string name, std::function<void(CLI::App& parent_app)> setup,
                 std::string parent = "");
};

void set_exit_code(int code);
int exit_code();

}  // namespace pinmask::cli
