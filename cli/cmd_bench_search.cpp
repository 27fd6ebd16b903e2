// `pinmask bench search`: incremental moves per second against full-FFT re-evaluation per second.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "bench/search_bench.hpp"
#include "cli/commands.hpp"
#include "core/errors/error.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    std::vector<int> sizes{16, 64, 256};
    double seconds = 0.5;
    bool json = false;
};

// The objective after one move at two geometries (n = 16 at 8 px per cell, the paper preset;
// n = 32 at 21 px per cell, the 3.45 um camera of bench period), with the per-cell ratio.
void print_objective(double seconds, bool json) {
    const auto rec = bench_objective({{16, 8}, {32, 21}}, seconds, 1);
    if (!json) {
        std::printf(
            "\nobjective after one move (analytic Wiener, optimal filter, O(n^2) alias tables):\n");
        std::printf("%6s %4s %5s %14s %18s %16s\n", "n", "ppc", "K", "moves/s", "full evals/s",
                    "moves/s x n^2");
    }
    for (const auto& r : rec) {
        if (json) {
            std::cout << nlohmann::json{{"objective_n", r.n},
                                        {"pixels_per_cell", r.pixels_per_cell},
                                        {"holes", r.holes},
                                        {"objective_moves_per_second", r.moves_per_second},
                                        {"full_evals_per_second", r.full_evals_per_second},
                                        {"per_cell_rate", r.per_cell_rate}}
                             .dump()
                      << "\n";
        } else {
            std::printf("%6d %4d %5d %14.4g %18.4g %16.4g\n", r.n, r.pixels_per_cell, r.holes,
                        r.moves_per_second, r.full_evals_per_second, r.per_cell_rate);
        }
    }
    if (!json && rec.size() == 2) {
        const double ratio = rec[0].per_cell_rate / rec[1].per_cell_rate;
        std::printf("per-cell ratio 16x16@8px / 32x32@21px: %.2f (target <= 4: %s)\n", ratio,
                    ratio <= 4.0 ? "met" : "not met");
    }
}

void run(const Options& o) {
    for (int n : o.sizes) {
        if (n < 4 || n > 4096) throw invalid_field("--sizes", std::to_string(n), "must be 4..4096");
    }
    if (!(o.seconds > 0.0))
        throw invalid_field("--seconds", std::to_string(o.seconds), "must be > 0");
    const auto records = bench_search(o.sizes, o.seconds, 1);
    if (!o.json) {
        std::printf("%6s %5s %16s %18s %9s\n", "n", "K", "moves/s", "full evals/s", "speedup");
    }
    for (const auto& r : records) {
        if (o.json) {
            std::cout << nlohmann::json{{"n", r.n},
                                        {"holes", r.holes},
                                        {"moves_per_second", r.moves_per_second},
                                        {"full_evals_per_second", r.full_evals_per_second},
                                        {"speedup", r.speedup}}
                             .dump()
                      << "\n";
        } else {
            std::printf("%6d %5d %16.4g %18.4g %9.1f\n", r.n, r.holes, r.moves_per_second,
                        r.full_evals_per_second, r.speedup);
        }
    }
    print_objective(o.seconds, o.json);
}

}  // namespace

void add_bench_search(CLI::App& bench) {
    auto opts = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "search",
        "Incremental single-pinhole moves per second (P^ updated by two plane waves, the "
        "autocorrelation in O(K), legality in O(1)) beside full re-evaluation per second "
        "(FFT of the pattern and inverse FFT of |P^|^2), one core, same run.");
    cmd->add_option("--sizes", opts->sizes, "Pattern sizes n")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--seconds", opts->seconds, "Seconds per size and method")
        ->capture_default_str();
    cmd->add_flag("--json", opts->json,
                  "One JSON record per line: n, holes, moves_per_second, "
                  "full_evals_per_second, speedup");
    cmd->footer("Example: pinmask bench search --sizes 16,64,256 --json");
    cmd->callback([opts] { run(*opts); });
}

}  // namespace pinmask::cli
