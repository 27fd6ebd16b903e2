// pinmask: the command-line tool. Wires the subcommands (cli/commands.hpp) and maps errors to exit
// codes.
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string_view>

#include "cli/commands.hpp"
#include "cli/options/command_flags.hpp"
#include "cli/options/fft_setup.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/options/option_checks.hpp"
#include "cli/outputs/interrupt.hpp"
#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"
#include "core/files/path_text.hpp"
#include "core/limits/allocator.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/units.hpp"
#include "core/version.hpp"
#include "optimize/search/mpi/mpi_comm.hpp"

namespace {

// Prints an input error (exit 2). Under mpirun, before any command started MPI, every rank parsed
// the same flags and read the same files, so the error is every rank's alike: rank 0 alone prints
// it, and the others leave only once it has (mpirun ends the job at the first rank that exits
// non-zero, which could otherwise cut rank 0 short). Once a command has started MPI, it routes
// its set-up errors to rank 0 itself (search, sweep, decode --batch): every rank that gets here
// prints.
int report_input_error(const std::function<void()>& print) {
    using namespace pinmask;
    if (!launched_by_mpi() || mpi_active()) {
        print();
        return 2;
    }
    try {
        RankComm& comm = world_comm();
        if (comm.rank() == 0) print();
        comm.barrier();
    } catch (const std::exception&) {
        print();  // MPI did not start: say it here rather than not at all
    }
    return 2;
}

// "--name=" with nothing after '=': CLI11 would take the next argument as the value (so
// `--stats= --json` wrote the stats to a file named "--json"). Returns the first such argument.
std::string_view empty_assigned_value(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if (a == "--") break;  // what follows is positional
        if (a.size() > 3 && a.substr(0, 2) == "--" && a.back() == '=' &&
            a.find('=') == a.size() - 1) {
            return a;
        }
    }
    return {};
}

// A filesystem error on a path the user named (too long, not permitted, read-only, a missing
// folder): an input problem, said with the path and the system's reason. Other filesystem
// failures (disk full, I/O) stay runtime failures.
bool is_path_error(const std::filesystem::filesystem_error& e) {
    switch (e.code().value()) {
        case ENAMETOOLONG:
        case EACCES:
        case EPERM:
        case EROFS:
        case ENOENT:
        case ENOTDIR:
        case EISDIR:
        case ELOOP:
        case EEXIST:
            return true;
        default:
            return false;
    }
}

std::string describe(const std::filesystem::filesystem_error& e) {
    std::string what = "'" + e.path1().string() + "': " + e.code().message();
    if (!e.path2().empty()) what += " (with '" + e.path2().string() + "')";
    return what;
}

// CLI11's ExtrasError lists the left-over arguments in reverse order ("20 --photons"), which reads
// as garbage. Says instead, in command-line order, what the command did not take, and where its
// options are listed.
std::string describe_extras(const CLI::App& app) {
    const CLI::App* cmd = &app;
    std::string path = "pinmask";
    while (!cmd->get_subcommands().empty()) {
        cmd = cmd->get_subcommands().front();
        path += " " + cmd->get_name();
    }
    std::vector<std::string> left = cmd->remaining(false);
    if (left.empty()) left = app.remaining(true);
    std::string options, values;
    for (const std::string& a : left) {
        std::string& list = (a.size() > 1 && a[0] == '-') ? options : values;
        list += (list.empty() ? "" : ", ") + a;
    }
    std::string what;
    if (!options.empty()) what = "does not take the option(s) " + options;
    if (!values.empty()) {
        what += (what.empty() ? "" : "; ") + std::string("has no place for the value(s) ") + values;
    }
    return path + " " + what + " (see '" + path + " --help')";
}

}  // namespace

int main(int argc, char** argv) {
    using namespace pinmask;
    keep_freed_memory();  // core/limits/allocator.hpp: no page faults re-taken per decode or
                          // evaluation
    // A write past the file-size limit (ulimit -f) then fails with EFBIG, which the writers
    // report ("could not write '<path>': File too large", exit 1, temporaries removed), instead
    // of killing the process mid-write with SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    cli::install_cleanup_on_signal();  // a signal leaves no *.tmp-* file behind
    if (const std::string_view bad = empty_assigned_value(argc, argv); !bad.empty()) {
        std::cerr << "pinmask: error: " << bad.substr(0, bad.size() - 1)
                  << ": the value after '=' is empty (give a value, or leave the option out)\n";
        return 2;
    }
    // Every argument is recorded in some JSON file (configs, sidecars, summaries), which holds
    // UTF-8 text only: a name with other bytes failed with exit 1 after the work.
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if (invalid_utf8_at(a) == std::string_view::npos) continue;
        const bool after_flag = i > 1 && argv[i - 1][0] == '-' && a.substr(0, 1) != "-";
        std::cerr << "pinmask: error: "
                  << (after_flag ? std::string(argv[i - 1]) + " = " : std::string("argument "))
                  << "'" << printable_text(a) << "': is not UTF-8 text (its byte "
                  << invalid_utf8_at(a)
                  << " begins no UTF-8 character); pinmask records its inputs' names in JSON, "
                     "which holds UTF-8 only: "
                     "rename the file (or give the value in UTF-8)\n";
        return 2;
    }
    CLI::App app{
        "pinmask: design, simulate, export and decode coded pinhole-array masks for a coded "
        "pinhole lens camera.\nUnits take suffixes (440um, 55mm, 6m, 550nm); plain numbers are "
        "SI. Exit codes: 0 ok, 1 runtime failure, 2 usage or invalid input, 3 the time limit "
        "PINMASK_TIME_LIMIT (e.g. 90s, 2m, 1.5h; off unless set) was spent: decode --batch "
        "keeps the captures it finished, check gives no verdict.",
        "pinmask"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "pinmask " PINMASK_VERSION);
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
    cli::add_export(app, exit_code);
    cli::add_check(app, exit_code);
    cli::add_depth(app);
    cli::add_depthmap(app);
    cli::add_sweep(app);
    CLI::App& bench = cli::add_bench(app);
    cli::add_bench_plan(bench);
    cli::add_bench_decode(bench);
    cli::add_bench_search(bench);
    cli::add_bench_export(bench);
    cli::add_bench_error_time(bench);
    cli::add_bench_period(bench);
    cli::add_bench_depth(bench);
    cli::add_bench_depthmap(bench);
    cli::add_bench_calibrate(bench);
    cli::refuse_negative_unsigned(app);     // --seed -1 must not wrap to 2^64 - 1
    cli::refuse_non_decimal_integers(app);  // --sides 0x8, --layer 010 (octal 8)
    enable_input_protection();              // no output may replace a file this run read
    try {
        memory_limit_bytes();  // a bad PINMASK_MEMORY_LIMIT is refused by every command
        // The time budget starts here, once for the whole run (a bad value: every command).
        if (const auto seconds = time_limit_from_environment()) start_time_limit(*seconds);
        cli::configure_fft_for_process();
        app.parse(argc, argv);
        cli::print_fft_warnings();
    } catch (const CLI::ExtrasError&) {
        return report_input_error(
            [&] { std::cerr << "pinmask: error: " << describe_extras(app) << "\n"; });
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        return report_input_error([&] { app.exit(e); });
    } catch (const TimeLimitSpent& e) {
        std::cerr << "pinmask: stopped: " << cli::spell_flags(readable_numbers(e.what())) << "\n";
        return 3;
    } catch (const InvalidInput& e) {
        // Spelled for the command that ran (the deepest parsed subcommand): a field whose flag
        // that command lacks is named with the commands that have it.
        const CLI::App* ran = nullptr;
        for (auto subs = app.get_subcommands(); !subs.empty(); subs = ran->get_subcommands())
            ran = subs.back();
        const std::string what = readable_numbers(e.what());
        return report_input_error([&] {
            std::cerr << "pinmask: error: "
                      << (ran ? cli::spell_flags(what, *ran) : cli::spell_flags(what)) << "\n";
        });
    } catch (const std::filesystem::filesystem_error& e) {
        if (is_path_error(e)) {
            return report_input_error(
                [&] { std::cerr << "pinmask: error: cannot use " << describe(e) << "\n"; });
        }
        std::cerr << "pinmask: failed: " << describe(e) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "pinmask: failed: " << cli::spell_flags(readable_numbers(e.what())) << "\n";
        return 1;
    }
    return exit_code;
}
