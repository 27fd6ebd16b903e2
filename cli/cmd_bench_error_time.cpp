// `pinmask bench error-time`: PSNR against decode time of every decoder for one mask
// (bench/error_time_run.hpp), written by bench/error_time_files as CSV, a plot per SNR (SVG + PNG)
// and a Markdown table, with the resolved configuration; all files appear together.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench/error_time_files.hpp"
#include "bench/error_time_run.hpp"
#include "cli/commands.hpp"
#include "cli/options/number_lists.hpp"
#include "cli/outputs/error_time_json.hpp"
#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"
#include "core/units/units.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/mask_json.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

struct Options {
    std::optional<std::string> mask;
    std::optional<std::string> preset;
    std::string scenes = "letter-R,usaf";
    std::string snr = "30";
    std::string iters = "1,3,10,30,100,300,1000";
    std::string nsr = "1e-4,3e-4,1e-3,3e-3,1e-2,3e-2,1e-1";
    std::string tikhonov_lambda = "1e-4,3e-4,1e-3,3e-3,1e-2";
    double tv_lambda = 1e-3;
    int repeats = 5;
    std::uint64_t seed = 1;
    bool quick = false;
    std::string output;
    bool json = false;
};

// The mask: a file, or the paper preset = `pinmask generate --family paper --seed 1`.
Mask load_mask(const Options& o, std::string& source) {
    if (o.mask && o.preset) {
        throw invalid_field("--preset", *o.preset, "give either a mask file or --preset, not both");
    }
    if (o.mask) {
        source = *o.mask;
        return io::read_mask_file(*o.mask);
    }
    source = "preset paper (pinmask generate --family paper --seed 1)";
    return error_time_paper_mask();
}

void run(const Options& o) {
    // Flags first, before any work.
    ErrorTimeOptions et;
    et.snr_db = number_list(o.snr, "--snr");
    et.iterations = count_list(o.iters, "--iters");
    et.wiener_nsr = number_list(o.nsr, "--nsr");
    et.tikhonov_lambda = number_list(o.tikhonov_lambda, "--tikhonov-lambda");
    et.tv_lambda = o.tv_lambda;
    et.repeats = o.repeats;
    et.seed = o.seed;
    if (o.quick) {
        et.iterations = {1, 10, 100};
        et.wiener_nsr = {1e-3, 1e-2};
        et.tikhonov_lambda = {1e-3};
        et.repeats = 1;
    }
    et.validate();
    const std::vector<std::string> scene_names = item_list(o.scenes, "--scenes");
    std::vector<SceneSpec> specs;
    for (const auto& s : scene_names) specs.push_back(scene_from_name(s));
    fs::path out_dir(o.output);
    if (!out_dir.has_filename()) out_dir = out_dir.parent_path();  // "out/" names "out"
    check_output_folder(out_dir, "-o");
    const fs::path parent = out_dir.parent_path();
    if (!parent.empty() && !fs::is_directory(parent)) {
        throw invalid_field("-o", o.output, "its parent directory does not exist");
    }

    std::string source;
    const Mask mask = load_mask(o, source);
    const ErrorTimeSetup setup = error_time_setup(mask, specs);
    const int m = setup.period_px;
    std::string last;
    et.progress = [&](const std::string& msg) {
        // One stderr line per (SNR, scene, decoder): the text up to the decoder's setting.
        // msg = "snr S dB, SCENE, DECODER[ PARAM VALUE][, K iterations]"
        const std::size_t a = msg.find(", "), b = msg.find(", ", a + 2);
        const std::size_t c = msg.find_first_of(" ,", b + 2);
        const std::string head = msg.substr(0, c);
        if (head != last) std::cerr << "error-time: " << head << "\n";
        last = head;
    };
    std::cerr << "error-time: mask " << source << ", " << m << " x " << m << " period, kernel "
              << kernel_model_name(setup.kernel.model) << "; timing on one thread\n";
    const ErrorTimeResult r = run_error_time_bench(setup, et, source);

    const ordered_json config =
        error_time_config_json(mask, source, setup, scene_names, et, o.quick);
    const ErrorTimeFiles files = write_error_time_files(out_dir, r, config.dump(2) + "\n");
    if (o.json) {
        std::cout << error_time_summary_json(r, out_dir, files.plots).dump() << "\n";
        return;
    }
    std::cout << r.markdown << "\nwrote " << files.count << " files to " << out_dir.string()
              << "\n";
}

}  // namespace

void add_bench_error_time(CLI::App& bench) {
    auto o = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "error-time",
        "PSNR against decode time of every decoder for one mask: Wiener at several NSR, "
        "gradient Tikhonov at several lambda, TV-L2, TVQC and Richardson-Lucy after 1..1000 "
        "iterations, on simulated one-period captures with Gaussian noise at each SNR. "
        "Writes CSV, a plot per SNR (SVG + PNG) and a Markdown table of the best point per "
        "decoder.");
    auto* mask = cmd->add_option("mask", o->mask, "Mask file (*.mask.json)");
    cmd->add_option("--preset", o->preset,
                    "Use a built-in mask instead of a file: paper = `pinmask generate "
                    "--family paper --seed 1` (the default when no mask is given)")
        ->check(CLI::IsMember({"paper"}))
        ->excludes(mask);
    cmd->add_option("--scenes", o->scenes,
                    "Comma-separated scenes (letter-R, usaf, siemens-star, checker, point, "
                    "natural, or image files), rendered at one period")
        ->capture_default_str();
    cmd->add_option("--snr", o->snr, "Comma-separated SNRs in dB (Gaussian noise)")
        ->capture_default_str();
    cmd->add_option("--iters", o->iters,
                    "Comma-separated iteration counts of the iterative decoders; each count "
                    "is a separate run (solver state is not resumable)")
        ->capture_default_str();
    cmd->add_option("--nsr", o->nsr, "Comma-separated Wiener noise-to-signal ratios")
        ->capture_default_str();
    cmd->add_option("--tikhonov-lambda", o->tikhonov_lambda,
                    "Comma-separated gradient-Tikhonov weights")
        ->capture_default_str();
    cmd->add_option("--tv-lambda", o->tv_lambda, "TV-L2 weight (> 0)")->capture_default_str();
    cmd->add_option("--repeats", o->repeats,
                    "Timed runs of a point faster than 0.25 s; the median is kept (>= 1)")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the noise")->capture_default_str();
    cmd->add_flag("--quick", o->quick,
                  "Small sweep for smoke tests: iterations 1,10,100, NSR 1e-3,1e-2, Tikhonov "
                  "1e-3, one timed run per point (overrides those flags)");
    cmd->add_option("-o,--output", o->output, "Output directory (created; its parent must exist)")
        ->required();
    cmd->add_flag("--json", o->json,
                  "Print the output paths, the best point per decoder and every curve point "
                  "as one JSON object on stdout");
    cmd->footer(
        "Files in the output directory: error_time.csv (every scene and setting), "
        "error_time_points.csv (means over scenes: the plotted points), error_time.md (best "
        "point per decoder), error_time_snrS.svg/.png (time on a log axis, PSNR on y, the "
        "paper's Wiener 0.004 s and TVQC 7.2 s marked as times), error_time.config.json.\n"
        "Time: CPU seconds of one decode on one thread (decoders and FFTW are single-threaded, "
        "so this is the wall time of an idle machine; wall time is in the CSV), filter or "
        "operator set-up included, FFTW plans made before timing. TVQC's eps comes from the "
        "true noise sigma (l1-magic rule); Tikhonov uses the gradient regulariser. The "
        "paper's timings come from its own machine and code.\n"
        "Example: pinmask bench error-time --preset paper --scenes letter-R,usaf --snr 30 "
        "-o bench-out/");
    cmd->callback([o] { run(*o); });
}

}  // namespace pinmask::cli
