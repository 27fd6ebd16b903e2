// The subcommands: each cli/cmd_*.cpp defines one add_* that adds its subcommand (options,
// --help, callback) to the given app; main() calls them in --help order. A callback throws pinmask
// errors, which main maps to exit codes (InvalidInput -> 2, other errors -> 1); a command that
// finishes with a verdict other than "ok" (check: violations found) stores its exit code in the
// int main passes and returns.
#pragma once

#include <CLI/CLI.hpp>

namespace pinmask::cli {

void add_design(CLI::App& app);
void add_generate(CLI::App& app);
void add_psf(CLI::App& app);
void add_simulate(CLI::App& app);
void add_decode(CLI::App& app);
void add_search(CLI::App& app);
void add_score(CLI::App& app);
void add_calibrate(CLI::App& app);
void add_compare(CLI::App& app);
void add_export(CLI::App& app, int& exit_code);  // exit_code = 1 when the DRC finds violations
void add_check(CLI::App& app, int& exit_code);   // exit_code = 1 when violations are found
void add_depth(CLI::App& app);
void add_depthmap(CLI::App& app);
void add_sweep(CLI::App& app);

// `pinmask bench`: returns the bench app, the parent of the add_bench_* subcommands.
CLI::App& add_bench(CLI::App& app);
void add_bench_plan(CLI::App& bench);
void add_bench_decode(CLI::App& bench);
void add_bench_search(CLI::App& bench);
void add_bench_export(CLI::App& bench);
void add_bench_error_time(CLI::App& bench);
void add_bench_period(CLI::App& bench);
void add_bench_depth(CLI::App& bench);
void add_bench_depthmap(CLI::App& bench);
void add_bench_calibrate(CLI::App& bench);

}  // namespace pinmask::cli
