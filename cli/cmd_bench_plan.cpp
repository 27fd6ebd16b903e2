// `pinmask bench plan`: measures (FFTW_MEASURE) and remembers the FFT plans of the sizes a
// camera uses, filling the wisdom cache so later commands start at once; prints the time each
// plan took (a plan already in the cache is rebuilt from it in well under a millisecond).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/options/fft_setup.hpp"
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/units/units.hpp"
#include "decode/solvers/convolution.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    std::vector<std::string> sizes{"128", "480x720"};
    bool linear = true;
    int threads = 0;
};

void run(const Options& o) {
    if (o.threads != 0) set_fft_threads(o.threads);
    std::vector<std::pair<int, int>> shapes;
    for (const std::string& s : o.sizes) {
        const auto x = s.find('x');
        const double r = parse_number(x == std::string::npos ? s : s.substr(0, x), "--sizes");
        const double c = x == std::string::npos ? r : parse_number(s.substr(x + 1), "--sizes");
        if (!(r >= 1 && r <= 16384 && c >= 1 && c <= 16384) || r != int(r) || c != int(c))
            throw invalid_field("--sizes", s, "must be N or RxC with integer sides 1..16384");
        shapes.emplace_back(int(r), int(c));
        // The linear model's grid for a capture of this size and a PSF as large (the DiffuserCam
        // case): next 2^a 3^b 5^c 7^d of 2 n - 1 per axis.
        if (o.linear)
            shapes.emplace_back(next_fft_size(2 * int(r) - 1), next_fft_size(2 * int(c) - 1));
    }
    const WisdomChoice w = wisdom_choice_from_environment();
    if (w.path.empty()) {
        throw invalid_field("PINMASK_WISDOM", "off",
                            "bench plan fills the wisdom cache; unset PINMASK_WISDOM or give it "
                            "a path");
    }
    std::printf("wisdom file %s (%s), threads %d for >= 512 x 512\n", w.path.c_str(),
                w.source.c_str(), fft_threads());
    std::printf("%12s  %-7s %12s  %s\n", "size", "prec", "plan s", "from");
    for (auto [r, c] : shapes) {
        for (int single = 0; single < 2; ++single) {
            const FftPlanStats before = fft_plan_stats();
            if (single) {
                const Fft2f f(r, c);
            } else {
                const Fft2 f(r, c);
            }
            const FftPlanStats after = fft_plan_stats();
            const int made = after.plans - before.plans;
            const int cached = after.plans_from_wisdom - before.plans_from_wisdom;
            const std::string size = std::to_string(r) + "x" + std::to_string(c);
            std::printf("%12s  %-7s %12.4g  %s\n", size.c_str(), single ? "float" : "double",
                        after.planning_seconds - before.planning_seconds,
                        made == 0 ? "already planned" : (cached == made ? "wisdom" : "measured"));
        }
    }
    std::fflush(stdout);
}

}  // namespace

void add_bench_plan(CLI::App& bench) {
    auto opts = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "plan",
        "Measure (FFTW_MEASURE) the FFT plans of a camera's sizes, double and float, and "
        "remember them in the wisdom cache ($XDG_CACHE_HOME/pinmask/wisdom, or "
        "$PINMASK_WISDOM); prints each plan's time. Later commands rebuild these plans from "
        "the cache at once, with the same rounding every run.");
    cmd->add_option("--sizes", opts->sizes,
                    "Capture sizes: N (N x N pixels) or RxC (rows x cols), comma-separated; "
                    "the paper: one period 128 and the sensor 480x720")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_flag("!--no-linear", opts->linear,
                  "Skip the linear model's padded grid (next 2^a3^b5^c7^d of 2 N - 1) that "
                  "each size also gets by default");
    cmd->add_option("--threads", opts->threads,
                    "FFTW threads for plans of >= 512 x 512 (default: all cores)")
        ->check(CLI::Range(1, 64));
    cmd->footer("Example: pinmask bench plan --sizes 128,480x720,300x400");
    cmd->callback([opts] { run(*opts); });
}

}  // namespace pinmask::cli
