// `pinmask bench`: the parent of the benchmark subcommands (decode, search, export, error-time),
// each registered from its own file with parent "bench".
#include "cli/command.hpp"

namespace pinmask::cli {
namespace {

const Registration kBench(100, "bench", [](CLI::App& app) {
    auto* bench = app.add_subcommand(
        "bench",
        "Benchmarks: each prints our figure beside a reference timed in the same run "
        "(e.g. the bare FFTW transform pair), as a ratio. Timings depend on the machine.");
    bench->require_subcommand(1);
});

}  // namespace
}  // namespace pinmask::cli
