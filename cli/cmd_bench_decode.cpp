// `pinmask bench decode`: time per call of each decoder beside a bare FFTW r2c + c2r pair of the
// same size, timed in the same run, as a ratio.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/decode_bench.hpp"
#include "cli/command.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    DecodeBenchOptions bench;
    bool json = false;
};

void run(const Options& o) {
    if (!o.json) {
        std::fprintf(stderr, "timing %zu size(s), %d batch(es) per figure...\n",
                     o.bench.sizes.size(), o.bench.repeat);
    }
    const auto records = bench_decode(o.bench);
    if (!o.json) {
        std::printf("%6s  %-18s %14s %14s %8s  %s\n", "size", "method", "s/call", "fft pair s",
                    "ratio", "note");
    }
    for (const auto& r : records) {
        if (o.json) {
            std::cout << nlohmann::json{{"method", r.method},
                                        {"size", r.size},
                                        {"seconds_per_call", r.seconds_per_call},
                                        {"fft_pair_seconds", r.fft_pair_seconds},
                                        {"ratio", r.ratio}}
                             .dump()
                      << "\n";
        } else {
            std::string note;
            if (r.method == "tvqc_to_tolerance") {
                note = std::to_string(r.iterations) + " iterations" +
                       (r.converged ? "" : " (cap reached, not converged)");
            }
            std::printf("%6d  %-18s %14.4g %14.4g %8.2f  %s\n", r.size, r.method.c_str(),
                        r.seconds_per_call, r.fft_pair_seconds, r.ratio, note.c_str());
        }
    }
}

const Registration kBenchDecode(
    10, "decode",
    [](CLI::App& bench) {
        auto opts = std::make_shared<Options>();
        auto* cmd = bench.add_subcommand(
            "decode",
            "Decoder time per call on one N x N channel (cyclic model, a seeded 20-pinhole PSF "
            "and scene, 1% noise) beside a bare FFTW r2c + c2r pair of the same size timed in "
            "the same run, as a ratio. Methods: wiener and tikhonov (precomputed filter applied), "
            "one TV-L2 ADMM iteration, TVQC run to tolerance 1e-4 (iterations reported), one "
            "Richardson-Lucy iteration. Each figure is the minimum over --repeat timed batches.");
        cmd->add_option("--sizes", opts->bench.sizes,
                        "Channel sizes N (pixels, 16..8192); 1024 adds ~20 s, mostly TVQC")
            ->delimiter(',')
            ->capture_default_str();
        cmd->add_option("--repeat", opts->bench.repeat,
                        "Timed batches per figure (>= 1); each batch lasts >= 20 ms")
            ->capture_default_str();
        cmd->add_option("--tvqc-max-iterations", opts->bench.tvqc_max_iterations,
                        "Iteration cap of the TVQC run (>= 1)")
            ->capture_default_str();
        cmd->add_flag("--json", opts->json,
                      "One JSON record per line: method, size, seconds_per_call, "
                      "fft_pair_seconds, ratio");
        cmd->footer(
            "Example: pinmask bench decode --sizes 128,512,1024 --repeat 5 --json\n"
            "Timings depend on the machine and its load; the ratio to the FFT pair is the "
            "figure to compare.");
        cmd->callback([opts] { run(*opts); });
    },
    "bench");

}  // namespace
}  // namespace pinmask::cli
