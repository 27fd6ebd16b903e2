// `pinmask bench`: the parent of the benchmark subcommands (plan, decode, search, export,
// error-time, period, calibrate); main adds each of them to the app this returns.
#include "cli/commands.hpp"

namespace pinmask::cli {

CLI::App& add_bench(CLI::App& app) {
    auto* bench = app.add_subcommand(
        "bench",
        "Benchmarks: each prints our figure beside a reference timed in the same run "
        "(e.g. the bare FFTW transform pair), as a ratio. Timings depend on the machine.");
    bench->require_subcommand(1);
    return *bench;
}

}  // namespace pinmask::cli
