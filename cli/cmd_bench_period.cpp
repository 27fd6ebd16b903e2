// `pinmask bench period`: the period check's cost beside a Wiener decode of the same capture.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/period_bench.hpp"
#include "cli/commands.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    PeriodBenchOptions bench;
    bool json = false;
};

void run(const Options& o) {
    if (!o.json) std::fprintf(stderr, "simulating and timing (%d runs each)...\n", o.bench.repeat);
    const PeriodBenchResult r = bench_period(o.bench);
    const double frame_ratio = r.check_seconds / r.wiener_frame_seconds;
    const double period_ratio = r.check_seconds / r.wiener_period_seconds;
    if (o.json) {
        std::cout << nlohmann::json{{"rows", r.rows},
                                    {"cols", r.cols},
                                    {"period_px", r.period_px},
                                    {"check_seconds", r.check_seconds},
                                    {"wiener_frame_seconds", r.wiener_frame_seconds},
                                    {"wiener_period_seconds", r.wiener_period_seconds},
                                    {"check_over_wiener_frame", frame_ratio},
                                    {"check_over_wiener_period", period_ratio},
                                    {"check_matches", r.check_matches},
                                    {"check_early_exit", r.check_early_exit},
                                    {"doubted_check_seconds", r.doubted_check_seconds},
                                    {"doubted_check_over_wiener_frame",
                                     r.doubted_check_seconds / r.wiener_frame_seconds},
                                    {"doubted_matches", r.doubted_matches},
                                    {"doubted_early_exit", r.doubted_early_exit}}
                         .dump()
                  << "\n";
        return;
    }
    std::printf("capture %d x %d px, period %d px: check %s\n", r.rows, r.cols, r.period_px,
                r.check_matches ? "matches the PSF" : "MISMATCH (a false warning)");
    std::printf("  period check                 %10.4g s\n", r.check_seconds);
    std::printf("  Wiener decode, whole frame   %10.4g s   check / decode = %.3f\n",
                r.wiener_frame_seconds, frame_ratio);
    std::printf("  Wiener decode, one period    %10.4g s   check / decode = %.3f\n",
                r.wiener_period_seconds, period_ratio);
    std::printf("  (the early exit %s)\n",
                r.check_early_exit ? "decided both axes" : "doubted: the full search ran");
    std::printf("a capture the early exit doubts (natural scene, 10 dB): check %s%s\n",
                r.doubted_matches ? "consistent with the PSF" : "MISMATCH (a false warning)",
                r.doubted_early_exit ? " (early exit taken)" : "");
    std::printf(
        "  period check, full search    %10.4g s   / whole-frame decode = %.3f, / "
        "one-period decode = %.1f\n",
        r.doubted_check_seconds, r.doubted_check_seconds / r.wiener_frame_seconds,
        r.doubted_check_seconds / r.wiener_period_seconds);
}

}  // namespace

void add_bench_period(CLI::App& bench) {
    auto opts = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "period",
        "Cost of decode's period check beside a Wiener decode of the same capture (the "
        "machine-vision camera: 3.45 um pixels, 21 px per cell, 336 px period, 30 dB), timed in "
        "the same run; each figure the minimum over --repeat runs.");
    cmd->footer("Example: pinmask bench period --rows 2048 --cols 2448");
    cmd->add_option("--rows", opts->bench.rows, "Sensor rows (672..8192)")->capture_default_str();
    cmd->add_option("--cols", opts->bench.cols, "Sensor columns (672..8192)")
        ->capture_default_str();
    cmd->add_option("--repeat", opts->bench.repeat, "Runs per figure (>= 1)")
        ->capture_default_str();
    cmd->add_flag("--json", opts->json, "One JSON object on stdout");
    cmd->callback([opts] { run(*opts); });
}

}  // namespace pinmask::cli
