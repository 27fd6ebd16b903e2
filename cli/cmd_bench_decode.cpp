// `pinmask bench decode`: time per call of each decoder beside bare FFTW r2c + c2r pairs of the
// same size (FFTW_MEASURE, double and float) timed in the same run, as ratios.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/decode_bench.hpp"
#include "cli/commands.hpp"
#include "core/errors/error.hpp"
#include "core/units/units.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    DecodeBenchOptions bench;
    std::vector<std::string> sizes{"128", "512"};
    bool json = false;
};

// "N" -> N x N; "RxC" -> an extra shape.
void parse_sizes(Options& o) {
    o.bench.sizes.clear();
    o.bench.shapes.clear();
    for (const std::string& s : o.sizes) {
        const auto x = s.find('x');
        if (x == std::string::npos) {
            o.bench.sizes.push_back(static_cast<int>(parse_number(s, "--sizes")));
        } else {
            o.bench.shapes.emplace_back(static_cast<int>(parse_number(s.substr(0, x), "--sizes")),
                                        static_cast<int>(parse_number(s.substr(x + 1), "--sizes")));
        }
    }
}

void run(Options& o) {
    parse_sizes(o);
    if (!o.json) {
        std::fprintf(stderr, "timing %zu size(s), %d batch(es) per figure...\n",
                     o.bench.sizes.size() + o.bench.shapes.size(), o.bench.repeat);
    }
    const auto records = bench_decode(o.bench);
    if (!o.json) {
        std::printf("%9s %-7s %-30s %11s %11s %7s %11s %7s %6s  %s\n", "size", "model", "method",
                    "s/call", "pair s", "ratio", "pair f s", "ratio f", "floor", "note");
    }
    for (const auto& r : records) {
        if (o.json) {
            std::cout << nlohmann::json{{"method", r.method},
                                        {"rows", r.size},
                                        {"cols", r.cols},
                                        {"seconds_per_call", r.seconds_per_call},
                                        {"fft_pair_seconds", r.fft_pair_seconds},
                                        {"ratio", r.ratio},
                                        {"fft_pair_float_seconds", r.fft_pair_float_seconds},
                                        {"ratio_float", r.ratio_float},
                                        {"iterations", r.iterations},
                                        {"converged", r.converged},
                                        {"model", r.model},
                                        {"fft_pairs", r.fft_pairs}}
                             .dump()
                      << "\n";
        } else {
            std::string note;
            if (r.method == "tvqc_to_tolerance" || r.method == "tv_l2_to_0.2dB") {
                note = std::to_string(r.iterations) + " iterations" +
                       (r.converged ? "" : " (cap reached, not converged)");
            }
            const std::string size = std::to_string(r.size) + "x" + std::to_string(r.cols);
            // The floor: the method's FFT pairs (its transforms, nothing else), in pairs.
            const std::string floor = r.fft_pairs > 0 ? std::to_string(r.fft_pairs) : "-";
            std::printf("%9s %-7s %-30s %11.4g %11.4g %7.2f %11.4g %7.2f %6s  %s\n", size.c_str(),
                        r.model.c_str(), r.method.c_str(), r.seconds_per_call, r.fft_pair_seconds,
                        r.ratio, r.fft_pair_float_seconds, r.ratio_float, floor.c_str(),
                        note.c_str());
        }
    }
}

}  // namespace

void add_bench_decode(CLI::App& bench) {
    auto opts = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "decode",
        "Decoder time per call on one channel (cyclic model, a seeded 20-pinhole PSF and "
        "scene, 1% noise) beside bare FFTW r2c + c2r pairs of the same size planned with "
        "FFTW_MEASURE (double and float), timed in the same run, as ratios to each. Methods: "
        "wiener and tikhonov (precomputed filter applied; wiener also in float32), one TV-L2 "
        "ADMM iteration (double and float32), TV-L2 iterations to 0.2 dB of converged on the "
        "paper problem (sizes 16 n_px up to 256), TVQC run to tolerance 1e-4 and one TVQC "
        "iteration, one Richardson-Lucy iteration. Linear model (zero-padded, cropped; off with "
        "--no-linear): each size is the padded grid of a capture of half its size per axis "
        "and a spread PSF of the other half (600x800: a 300 x 400 capture, as the DiffuserCam "
        "hand); one float32 iteration of TV-L2 with x >= 0, TVQC and Richardson-Lucy. The "
        "floor column is the FFT pairs the method's transforms cost per call (iteration): "
        "ratio f at or near it means nothing but FFTW is left. Each figure is the minimum over "
        "--repeat timed batches.");
    cmd->add_option("--sizes", opts->sizes,
                    "Channel sizes: N (N x N pixels) or RxC, each side 16..8192; 1024 adds "
                    "~20 s, mostly TVQC")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--repeat", opts->bench.repeat,
                    "Timed batches per figure (>= 1); each batch lasts >= 20 ms")
        ->capture_default_str();
    cmd->add_option("--tvqc-max-iterations", opts->bench.tvqc_max_iterations,
                    "Iteration cap of the TVQC run (>= 1)")
        ->capture_default_str();
    cmd->add_option("--threads", opts->bench.threads,
                    "FFTW threads of our transforms and of the reference pairs alike (1..1024; "
                    "only sizes from 512 x 512 up use more than one)")
        ->capture_default_str();
    cmd->add_flag("--cpu-time", opts->bench.cpu_time,
                  "Time this thread's CPU time instead of wall time (for a loaded machine; use "
                  "with --threads 1)");
    cmd->add_flag("--linear,!--no-linear", opts->bench.linear,
                  "Also time the linear (zero-padded) model's iterations (default on)");
    cmd->add_flag("--json", opts->json,
                  "One JSON record per line: method, rows, cols, seconds_per_call, "
                  "fft_pair_seconds, ratio, fft_pair_float_seconds, ratio_float, iterations, "
                  "converged, model, fft_pairs");
    cmd->footer(
        "Example: pinmask bench decode --sizes 128,600x800 --repeat 5\n"
        "Timings depend on the machine and its load; the ratios to the FFT pairs are the "
        "figures to compare. Our transforms use the process's planner (FFTW_MEASURE with "
        "the wisdom cache unless PINMASK_WISDOM=off).");
    cmd->callback([opts] { run(*opts); });
}

}  // namespace pinmask::cli
