// pinmask: the command-line tool. Wires the registered subcommands and maps errors to exit codes.
#include <algorithm>
#include <iostream>
#include <vector>

#include "cli/command.hpp"
#include "cli/fft_setup.hpp"
#include "cli/option_checks.hpp"
#include "core/error.hpp"
#include "core/output_set.hpp"
#include "core/resource_limits.hpp"
#include "core/units.hpp"

namespace pinmask::cli {
namespace {

struct Entry {
    int order;
    std::string name;
    std::function<void(CLI::App&)> setup;
    std::string parent;
};

std::vector<Entry>& registry() {
    static std::vector<Entry> entries;
    return entries;
}

int g_exit_code = 0;

}  // namespace

Registration::Registration(int order, std::string name, std::function<void(CLI::App&)> setup,
                           std::string parent) {
    registry().push_back({order, std::move(name), std::move(setup), std::move(parent)});
}

void set_exit_code(int code) { g_exit_code = code; }
int exit_code() { return g_exit_code; }

}  // namespace pinmask::cli

int main(int argc, char** argv) {
    using namespace pinmask;
    CLI::App app{
        "pinmask: design, simulate, export and decode coded pinhole-array masks for a coded "
        "pinhole lens camera.\nUnits take suffixes (440um, 55mm, 6m, 550nm); plain numbers are "
        "SI. Exit codes: 0 ok, 1 runtime failure, 2 usage or invalid input.",
        "pinmask"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "pinmask 0.1.0");
    auto& entries = cli::registry();
    std::sort(entries.begin(), entries.end(),
              [](const auto& a, const auto& b) { return a.order < b.order; });
    for (auto& e : entries) {
        if (e.parent.empty()) e.setup(app);
    }
    for (auto& e : entries) {
        if (!e.parent.empty()) e.setup(*app.get_subcommand(e.parent));
    }
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
    return cli::exit_code();
}
