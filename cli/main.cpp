// pinmask: the command-line tool. Wires the subcommands (cli/commands.hpp) and maps errors to exit
// codes.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/fft_setup.hpp"
#include "cli/option_checks.hpp"
#include "core/allocator.hpp"
#include "core/error.hpp"
#include "core/output_set.hpp"
#include "core/resource_limits.hpp"
#include "core/units.hpp"

int main(int argc, char** argv) {
    using namespace pinmask;
    keep_freed_memory();  // core/allocator.hpp: no page faults re-taken per decode or evaluation
    CLI::App app{
        "pinmask: design, simulate, export and decode coded pinhole-array masks for a coded "
        "pinhole lens camera.\nUnits take suffixes (440um, 55mm, 6m, 550nm); plain numbers are "
        "SI. Exit codes: 0 ok, 1 runtime failure, 2 usage or invalid input.",
        "pinmask"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "pinmask 0.1.0");
    int exit_code = 0;  // set by a command whose verdict is not "ok" (check: violations)
    cli::add_design(app);
    cli::add_generate(app);
    cli::add_psf(app);
    cli::add_simulate(app);
    cli::add_decode(app);
    cli::add_search(app);
    cli::add_score(app);
    cli::add_calibrate(app);
    cli::add_compare(app);
    cli::add_export(app);
    cli::add_check(app, exit_code);
    cli::add_depth(app);
    cli::add_sweep(app);
    CLI::App& bench = cli::add_bench(app);
    cli::add_bench_plan(bench);
    cli::add_bench_decode(bench);
    cli::add_bench_search(bench);
    cli::add_bench_export(bench);
    cli::add_bench_error_time(bench);
    cli::add_bench_period(bench);
    cli::refuse_negative_unsigned(app);  // --seed -1 must not wrap to 2^64 - 1
    enable_input_protection();           // no output may replace a file this run read
    try {
        memory_limit_bytes();  // a bad PINMASK_MEMORY_LIMIT is refused by every command
        cli::configure_fft_for_process();
        app.parse(argc, argv);
        cli::print_fft_warnings();
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    } catch (const InvalidInput& e) {
        std::cerr << "pinmask: error: " << readable_numbers(e.what()) << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "pinmask: failed: " << readable_numbers(e.what()) << "\n";
        return 1;
    }
    return exit_code;
}
