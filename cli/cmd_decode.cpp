// `pinmask decode`: capture + (mask | PSF file) -> image, with a resolved config and a stats file.
// Parse -> load the files -> decode_capture (decode/capture/capture_pipeline.hpp) -> render and
// write, all files staged and committed together so a failure leaves no output.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "cli/decode_batch.hpp"
#include "cli/options/decode_flags.hpp"
#include "cli/options/decode_inputs.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/outputs/decode_files.hpp"
#include "cli/outputs/decode_output.hpp"
#include "cli/outputs/decode_progress.hpp"
#include "cli/outputs/image_output.hpp"
#include "cli/outputs/interrupt.hpp"
#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_set.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/solvers/decode_method.hpp"
#include "io/psf_files.hpp"
#include "optimize/search/mpi/mpi_comm.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

void run_decode(DecodeCommand& r, BayerMode bayer) {
    const auto t_start = Clock::now();
    plan_outputs(
        {{"capture", r.capture},
         {"--mask", r.mask},
         {"--psf", r.psf},
         {"--dark", r.dark},
         {"--nsr-map", r.nsr_map},
         {"--psf (sidecar)", r.psf.empty() ? "" : io::psf_sidecar_path(r.psf)}},
        {{"-o", r.output}, {"-o (config)", r.output + ".config.json"}, {"--stats", r.stats}});
    // Everything that can be checked without reading pixels, first.
    const OutputKind kind = output_kind(r.output);
    const fs::path out_dir = fs::path(r.output).parent_path();
    if (!out_dir.empty() && !fs::is_directory(out_dir))
        throw invalid_field("-o", r.output, "the output directory does not exist");
    const std::optional<double> scale = parse_scale(r.scale);
    apply_refocus(r);  // a pitch at u that is not whole: exact geometry, linear model
    resolve_request(r);
    CaptureDecodeOptions options = capture_decode_options(r.request);
    // Per-iteration records cost an objective each iteration; only --stats and --json show them.
    options.decode.iterative.record_history = !r.stats.empty() || r.json;
    options.validate();
    auto explain = [&](const std::string& line) {
        if (r.explain) std::cerr << "decode: " << line << "\n";
    };
    json stats = {{"format", "pinmask-decode-stats"}, {"version", 2}};
    json timings;

    auto t0 = Clock::now();
    CaptureDecodeInputs inputs = load_inputs(r, bayer,
                                             options.background == BackgroundMode::kCorner ||
                                                 options.background == BackgroundMode::kAuto,
                                             stats);
    load_nsr_map(r, options.decode, stats);
    timings["load"] = seconds_since(t0);

    // Everything before the decode, so that the method (given, or chosen from the capture) is
    // known before it runs.
    const int channels = inputs.capture.n_channels();
    PreparedCapture prepared =
        naming_nsr_map(r, [&] { return prepare_capture(std::move(inputs), options); });
    DecodeOptions& d = prepared.decode;
    // Iterative methods stop on SIGINT/SIGTERM after their current iteration; the estimate so
    // far is then written like a finished one and marked interrupted.
    if (is_iterative(d.method)) {
        d.iterative.stop = &install_interrupt_flag();
        if (::isatty(2))
            std::cerr << "decode: " << decode_method_name(d.method) << ", up to "
                      << d.iterative.max_iterations
                      << " iterations; Ctrl-C stops and writes the estimate so far\n";
    }
    // Iterations finished over all channels, counted by the solvers: the progress lines.
    std::atomic<long long> iterations_done{0};
    d.iterative.iterations_done = &iterations_done;
    const long long most_iterations = static_cast<long long>(d.iterative.max_iterations) * channels;
    const bool iterative = is_iterative(d.method);
    std::optional<CaptureDecodeResult> decoded;
    run_with_decode_progress(most_iterations, iterative && !r.quiet, iterations_done, [&] {
        decoded = naming_nsr_map(r, [&] { return decode_prepared(std::move(prepared)); });
    });
    const CaptureDecodeResult& result = *decoded;
    const CaptureDecodeSummary& sum = result.summary;
    for (const std::string& note : sum.notes) explain(spell_flags(note));
    explain("FFT planning " + std::to_string(sum.seconds.fft_planning) + " s during the decode");
    print_decode_warnings(sum, r.quiet);
    add_summary_json(stats, timings, r, sum);
    check_output_range(result.estimate, kind);

    // Write: the image, its config and the stats appear together or not at all.
    t0 = Clock::now();
    warn_all_zero("pinmask", "the estimate", result.estimate,
                  "a very large --nsr or --lambda passes nothing; so does an all-zero capture");
    StagedFiles files;
    const StagedDecode staged =
        stage_decode_files(files, r, result.estimate, kind, scale, stats["chosen"]);
    warn_black_png(staged, r.bits);
    timings["write"] = seconds_since(t0);
    timings["total"] = seconds_since(t_start);
    stats["output"] = staged.output;
    stats["config"] = staged.config;
    stats["timings_s"] = timings;
    if (!r.stats.empty()) files.stage_bytes(r.stats, stats.dump(2) + "\n");
    files.commit();

    if (r.json) {
        std::cout << stats.dump(2) << "\n";
        return;
    }
    print_decode_summary(r, sum);
}

// Under mpirun every rank runs the batch. Set-up errors are every rank's alike: rank 0 reports,
// the others leave with the same code; a decode error on any rank is reported by rank 0 after
// every rank discarded its staged files (cli/decode_batch.hpp).
void run_batch_on_ranks(const DecodeCommand& r, const BatchRequest& b, BayerMode bayer) {
    RankComm& comm = world_comm();  // MPI starts here, and only under a launcher
    try {
        run_decode_batch(r, b, bayer, comm);
    } catch (const BatchQuietExit& q) {
        std::exit(q.code);
    } catch (const std::exception& e) {
        if (comm.size() == 1 || comm.rank() == 0) throw;
        std::exit(dynamic_cast<const InvalidInput*>(&e) ? 2 : 1);
    }
}

void setup(CLI::App& app) {
    auto o = std::make_shared<DecodeCommand>();
    auto* cmd = app.add_subcommand(
        "decode",
        "Decode a capture with a mask (PSF synthesised from it) or a measured PSF file; writes "
        "the image, OUT.config.json and optionally a stats file.");
    cmd->footer(kDecodeFooter);
    auto flags = std::make_shared<DecodeFlags>(add_decode_flags(*cmd, *o));
    auto* bayer =
        cmd->add_option("--bayer", o->bayer,
                        "Camera RAW captures and dark frames: sum2x2 (half-resolution grey, the "
                        "pixel pitch doubles) | green (alias g) | r | b; see "
                        "core/image/raw_io.hpp. Given with a TIFF, PNG or .npy: the file is a "
                        "single-channel Bayer mosaic, read as sum2x2 (green, r and b need the "
                        "colour-filter pattern only a RAW file holds). A PSF at the sensor's "
                        "full resolution is summed 2 x 2 as the capture (sum2x2) or refused")
            ->capture_default_str();
    auto batch = std::make_shared<BatchRequest>();
    cmd->add_option("--batch", batch->list,
                    "Decode many captures with one PSF and these flags: a directory (its .tif, "
                    ".tiff, .png, .npy, .jpg, .jpeg and camera RAW files) or a text file of paths, "
                    "one a line; -o is then a "
                    "folder, created when missing (STEM.EXT per capture, batch-summary.json). "
                    "Under mpirun the "
                    "captures are shared among the ranks. With PINMASK_TIME_LIMIT set (a "
                    "duration from the start of the run, e.g. 2h) the batch stops between "
                    "captures once it is spent: the captures finished are written, the others "
                    "are listed in batch-summary.json as not done, exit code 3");
    cmd->add_option("--batch-format", batch->format, "--batch outputs: tiff | png | npy")
        ->capture_default_str();
    cmd->add_flag("--batch-stats", batch->stats, "--batch: also write STEM.stats.json per capture");
    cmd->callback([cmd, o, flags, batch, bayer] {
        o->bayer_given = bayer->count() > 0;
        resolve_method(*o, *flags);
        refuse_ignored_output_flags(*cmd, *o, !batch->list.empty(), batch->format);
        if (!batch->list.empty()) return run_batch_on_ranks(*o, *batch, parse_bayer_mode(o->bayer));
        if (o->capture.empty())
            throw InvalidInput("decode needs a capture file (or --batch LIST_OR_DIR)");
        run_decode(*o, parse_bayer_mode(o->bayer));
    });
}

}  // namespace

void add_decode(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
