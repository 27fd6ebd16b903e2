// `pinmask decode`: capture + (mask | PSF file) -> image, with a resolved config and a stats file.
// Pipeline: load -> dark frame -> preprocessing (background, 2^K box downsampling) -> period
// check -> crop -> normalisation -> decode each channel (threads) -> write, all files staged and
// committed together so a failure leaves no output.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "cli/command.hpp"
#include "cli/decode_output.hpp"
#include "cli/interrupt.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/units.hpp"
#include "decode/capture.hpp"
#include "decode/period.hpp"
#include "design/working_distance.hpp"
#include "decode/preprocess.hpp"
#include "design/mask.hpp"
#include "design/psf.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The PSF (one channel, shared by every capture channel) and a description for the stats. A PSF
// file is renormalised to sum 1 by its reader; `counts` keeps the file's own values for
// --background corner, whose patch mean is in the counts the capture shares.
struct LoadedPsf {
    Image image;
    std::optional<Plane> counts;
    json info;
};

LoadedPsf load_psf(const DecodeRequest& r, bool need_counts) {
    if (r.mask.empty() && r.psf.empty()) {
        throw InvalidInput("decode needs the PSF: give --mask FILE.mask.json or --psf FILE");
    }
    LoadedPsf p;
    if (!r.psf.empty()) {
        io::PsfFile file = io::read_psf_file(r.psf);
        p.info = {{"source", "psf-file"}, {"path", r.psf}, {"sidecar", file.sidecar.has_value()}};
        if (file.sidecar) {
            p.info["mask_geometry_hash"] = file.sidecar->mask_geometry_hash;
            p.info["pixels_per_cell"] = file.sidecar->pixels_per_cell;
            p.info["kernel_model"] = file.sidecar->kernel_model;
        }
        p.image = Image(std::move(file.psf));
        if (need_counts) p.counts = read_image(r.psf).image.channels.at(0);
    } else {
        if (need_counts) {
            throw invalid_field("--background", "corner",
                                "needs a measured PSF (--psf): a PSF synthesised from a mask "
                                "has no camera background");
        }
        Mask mask = io::read_mask_file(r.mask);
        if (r.object_distance) {  // refocus: the PSF for an object at u (issue 12)
            const double u =
                parse_length_m(*r.object_distance, "--object-distance", AllowInfinity::kYes);
            check_object_distance(mask.camera, u, "--object-distance");
            mask = mask_at_distance(mask, u);
        }
        p.image = Image(mask_psf(mask));
        p.info = {{"source", "mask"},
                  {"path", r.mask},
                  {"mask_geometry_hash", geometry_hash(mask)},
                  {"pixels_per_cell", mask.psf.pixels_per_cell},
                  {"kernel_model", mask.psf.kernel.model}};
    }
    check_psf(p.image.channels[0], "PSF " + (r.psf.empty() ? r.mask : r.psf));
    p.info["rows"] = p.image.rows();
    p.info["cols"] = p.image.cols();
    return p;
}

std::string size_text(const Image& img) {
    return std::to_string(img.cols()) + " x " + std::to_string(img.rows()) + " x " +
           std::to_string(img.n_channels());
}

// Sum of the channels: the luminance the period check looks at.
Plane channel_sum(const Image& img) {
    Plane s = img.channels[0];
    for (std::size_t ch = 1; ch < img.channels.size(); ++ch) s += img.channels[ch];
    return s;
}

void run_decode(const DecodeRequest& r) {
    const auto t_start = Clock::now();
    // Everything that can be checked without reading pixels, first.
    const OutputKind kind = output_kind(r.output);
    const fs::path out_dir = fs::path(r.output).parent_path();
    if (!out_dir.empty() && !fs::is_directory(out_dir))
        throw invalid_field("-o", r.output, "the output directory does not exist");
    const CropSpec crop_spec = parse_crop(r.crop);
    const Background bg = parse_background(r.background);
    const std::optional<double> scale = parse_scale(r.scale);
    DecodeOptions dopt = decode_options(r);
    auto explain = [&](const std::string& text) {  // one "decode: " line per line of text
        if (!r.explain) return;
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);) std::cerr << "decode: " << line << "\n";
    };
    json stats = {{"format", "pinmask-decode-stats"}, {"version", 1}};
    json timings;

    // Load.
    auto t0 = Clock::now();
    LoadedImage loaded = read_image(r.capture);
    Image capture = std::move(loaded.image);
    check_image_finite(capture, "capture " + r.capture);
    LoadedPsf psf = load_psf(r, bg.mode == "corner");
    std::optional<Image> dark;
    if (!r.dark.empty()) {
        dark = read_image(r.dark).image;
        check_image_finite(*dark, "dark frame " + r.dark);
    }
    timings["load"] = seconds_since(t0);
    stats["capture"] = {{"path", r.capture},
                        {"rows", capture.rows()},
                        {"cols", capture.cols()},
                        {"channels", capture.n_channels()},
                        {"full_scale", loaded.full_scale}};
    stats["psf"] = psf.info;

    // Dark frame.
    t0 = Clock::now();
    if (dark) capture = subtract_dark(capture, *dark);
    timings["dark"] = seconds_since(t0);
    stats["dark"] =
        dark ? json{{"path", r.dark}, {"subtracted", true}} : json{{"subtracted", false}};

    // Preprocessing: background, downsampling (normalisation follows the crop).
    t0 = Clock::now();
    json backgrounds = json::array();
    if (bg.mode != "none") {
        // corner: the tutorial's scalar, from the PSF file's counts, off both PSF and capture.
        const double b = bg.mode == "corner" ? corner_background(*psf.counts) : bg.value;
        for (Plane& p : capture.channels) p -= b;
        if (psf.counts) psf.image.channels[0] = *psf.counts - b;
        backgrounds.push_back(b);
        explain("background " + std::to_string(b) + " subtracted from the capture" +
                (bg.mode == "corner" ? " and the PSF (mean of the PSF's rows/cols 5..14)" : ""));
    }
    for (Plane& p : capture.channels) p = box_downsample(p, r.downsample);
    for (Plane& p : psf.image.channels) p = box_downsample(p, r.downsample);
    check_psf(psf.image.channels[0], "PSF after preprocessing");
    timings["preprocess"] = seconds_since(t0);
    if (r.downsample > 0)
        explain("downsampled " + std::to_string(r.downsample) + " rounds of 2x2: capture " +
                size_text(capture) + ", PSF " + size_text(psf.image));

    // Period check on the full frame (luminance), against the PSF's size.
    t0 = Clock::now();
    const PeriodCheck period =
        check_period(channel_sum(capture), psf.image.rows(), psf.image.cols());
    timings["period_check"] = seconds_since(t0);
    stats["period_check"] = period_check_json(period);
    std::istringstream warnings(period_warning(period));
    for (std::string line; std::getline(warnings, line);)
        std::cerr << "pinmask: warning: " << line << "\n";
    explain(period_skip_note(period));

    // Crop.
    t0 = Clock::now();
    const CropWindow window =
        crop_window(capture.rows(), capture.cols(), psf.image.rows(), psf.image.cols(), crop_spec);
    capture = crop(capture, window);
    timings["crop"] = seconds_since(t0);
    stats["window"] = {{"x", window.col},
                       {"y", window.row},
                       {"cols", window.cols},
                       {"rows", window.rows},
                       {"mode", r.crop}};
    explain("decoding the window " + std::to_string(window.cols) + " x " +
            std::to_string(window.rows) + " at x=" + std::to_string(window.col) +
            ", y=" + std::to_string(window.row) + " (--crop " + r.crop + ")");

    // Normalisation of what is decoded.
    json norm = {{"mode", r.normalize}};
    if (r.normalize == "l2") {
        json cn = json::array(), pn = json::array();
        for (Plane& p : capture.channels) {
            cn.push_back(p.matrix().norm());
            p = l2_normalized(p, "capture window");
        }
        for (Plane& p : psf.image.channels) {
            pn.push_back(p.matrix().norm());
            p = l2_normalized(p, "PSF");
        }
        norm["capture_l2_norms"] = cn;
        norm["psf_l2_norms"] = pn;
    } else {
        json sums = json::array();
        for (Plane& p : psf.image.channels) {
            sums.push_back(p.sum());
            p /= p.sum();
        }
        norm["psf_sums"] = sums;
    }
    stats["preprocess"] = {{"background", {{"mode", bg.mode}, {"values", backgrounds}}},
                           {"downsample_rounds", r.downsample},
                           {"normalize", norm},
                           {"decoded_rows", capture.rows()},
                           {"decoded_cols", capture.cols()}};

    // Decode. Iterative methods stop on SIGINT/SIGTERM after their current iteration; the
    // estimate so far is then written like a finished one and marked interrupted.
    const bool iterative = dopt.method == DecodeMethod::kTv || dopt.method == DecodeMethod::kTvqc ||
                           dopt.method == DecodeMethod::kRichardsonLucy;
    if (iterative) {
        dopt.stop = &install_interrupt_flag();
        if (::isatty(2))
            std::cerr << "decode: " << r.method << ", up to " << dopt.max_iterations
                      << " iterations; Ctrl-C stops and writes the estimate so far\n";
    }
    t0 = Clock::now();
    const std::vector<DecodeResult> results = decode_channels(capture, psf.image.channels, dopt);
    timings["decode"] = seconds_since(t0);
    Image estimate;
    json channels = json::array(), per_channel = json::array();
    for (std::size_t ch = 0; ch < results.size(); ++ch) {
        const DecodeResult& d = results[ch];
        estimate.channels.push_back(d.image);
        json history = json::array();
        for (const auto& h : d.history)
            history.push_back({{"iteration", h.iteration},
                               {"seconds", h.seconds},
                               {"objective", h.objective},
                               {"residual", h.residual}});
        channels.push_back({{"channel", ch},
                            {"seconds", d.seconds},
                            {"iterations", d.iterations},
                            {"objective", d.objective},
                            {"residual", d.residual},
                            {"converged", d.converged},
                            {"interrupted", d.interrupted},
                            {"history", history}});
        per_channel.push_back(d.seconds);
    }
    timings["decode_channels"] = per_channel;
    const bool interrupted =
        std::any_of(results.begin(), results.end(), [](const auto& d) { return d.interrupted; });
    if (interrupted) {
        stats["interrupted"] = true;
        std::cerr << "pinmask: interrupted: writing the estimate after "
                  << results.front().iterations << " iterations (not converged)\n";
    }
    stats["channels"] = channels;
    check_image_finite(estimate, "decoded estimate");

    // Write: the image, its config and the stats appear together or not at all.
    t0 = Clock::now();
    const json config = config_json(r);
    StagedFiles files;
    json output = {{"path", r.output},
                   {"format", output_kind_name(kind)},
                   {"config", r.output + ".config.json"}};
    if (kind == OutputKind::kPng) {
        const ScaledImage png = scale_for_png(estimate, scale);
        files.stage(r.output,
                    [&](const fs::path& tmp) { write_output_image(tmp, png.image, kind, r.bits); });
        output["bits"] = r.bits;
        output["scaling"] = scale ? "factor" : "max";
        output["scale_factor"] = png.factor;
        output["max_value"] = png.max_value;
        if (png.max_value <= 0.0)
            std::cerr << "pinmask: warning: the estimate has no positive value; the PNG is black\n";
    } else {
        files.stage(r.output,
                    [&](const fs::path& tmp) { write_output_image(tmp, estimate, kind, r.bits); });
    }
    files.stage_bytes(r.output + ".config.json", config.dump(2) + "\n");
    timings["write"] = seconds_since(t0);
    timings["total"] = seconds_since(t_start);
    stats["output"] = output;
    stats["method"] = r.method;
    stats["config"] = config;
    stats["timings_s"] = timings;
    if (!r.stats.empty()) files.stage_bytes(r.stats, stats.dump(2) + "\n");
    files.commit();

    if (r.json) {
        std::cout << stats.dump(2) << "\n";
        return;
    }
    std::cout << "decode " << r.capture << " -> " << r.output << "\n"
              << "  method   " << r.method << " (" << r.model << " model)\n"
              << "  window   " << window.cols << " x " << window.rows << " at x=" << window.col
              << ", y=" << window.row << "\n";
    for (std::size_t ch = 0; ch < results.size(); ++ch)
        std::cout << "  channel " << ch << "  iterations " << results[ch].iterations
                  << "  residual " << results[ch].residual << "  objective "
                  << results[ch].objective << "  " << results[ch].seconds << " s"
                  << (results[ch].interrupted ? "  (interrupted)" : "") << "\n";
    std::cout << "  period   "
              << (period.checked()
                      ? (period.matches() ? "matches the PSF" : "MISMATCH (see warning)")
                      : "not checked (fewer than two periods)")
              << "\n  wrote    " << r.output << ", " << r.output << ".config.json"
              << (r.stats.empty() ? "" : ", " + r.stats) << "\n";
}

const char* kFooter = R"(
Steps: dark frame subtracted (same size, 1 or the capture's channels) -> --background ->
--downsample -> period check -> --crop -> --normalize -> decode each channel (RGB channels in
parallel threads) -> write.
Period: the PSF's size. The capture's own period is measured from its autocorrelation and a
mismatch is reported on stderr and in the stats (skipped, with the reason, when the capture
holds fewer than two periods along an axis).
Output: PNG clips negatives to 0 and multiplies by 1/max over all channels (or by --scale),
then writes 8- or 16-bit; .tif/.tiff (float32) and .npy (float32) hold the raw estimate.
Orientation: the output is in the decoded window's pixel grid, never flipped or mirrored: row 0
is the window's top row, column 0 its left column; a capture identical to the PSF decodes to a
point at (row floor(H/2), column floor(W/2)), the PSF's centre (deconvwnr convention).
Units: with --normalize none the PSF is scaled to unit sum and the estimate is in capture
counts; with --normalize l2 both are divided by their L2 norms (the DiffuserCam tutorial).
Also written: OUT.config.json (the resolved configuration) next to the output.
Ctrl-C (or SIGTERM) during tv, tvqc or rl ends the iteration early: the estimate so far is
written as usual and marked "interrupted" in the stats; a second Ctrl-C kills at once.

Examples:
  pinmask decode capture.tiff --mask paper.mask.json --dark dark.tiff -o scene.png --stats s.json
  pinmask decode raw.tif --psf psf.tif --model linear --background corner --downsample 2 \
      --normalize l2 --crop none --method tv --lambda 1e-4 --iters 100 -o hand.png)";

void setup(CLI::App& app) {
    auto o = std::make_shared<DecodeRequest>();
    auto* cmd = app.add_subcommand(
        "decode",
        "Decode a capture with a mask (PSF synthesised from it) or a measured PSF file; writes "
        "the image, OUT.config.json and optionally a stats file.");
    cmd->footer(kFooter);
    cmd->add_option("capture", o->capture,
                    "Capture image: TIFF (8/16-bit, float32), PNG (8/16-bit), .npy; grey or RGB")
        ->required();
    auto* mask =
        cmd->add_option("--mask", o->mask, "Mask file (*.mask.json); its PSF is synthesised");
    auto* psf = cmd->add_option("--psf", o->psf,
                                "PSF file (float TIFF or .npy, with its sidecar when present)");
    mask->excludes(psf);
    psf->excludes(mask);
    cmd->add_option("--object-distance", o->object_distance,
                    "With --mask: decode with the PSF for an object at this distance (e.g. 2m, "
                    "inf; refocusing after capture): kernel and whole pixels per cell at u")
        ->needs(mask);
    cmd->add_option("--dark", o->dark,
                    "Dark frame (capture through an all-opaque film), subtracted first; same size");
    cmd->add_option("--crop", o->crop,
                    "Window decoded: center (the period centred in the frame), none (whole frame, "
                    "PSF zero-padded), or X,Y (top-left column,row of one period)")
        ->capture_default_str();
    cmd->add_option("--method", o->method,
                    "wiener (closed form, deconvwnr) | tikhonov (closed form) | tv (TV-L2, "
                    "ADMM) | tvqc (min TV s.t. ||Ax - p||_2 <= eps) | rl (Richardson-Lucy)")
        ->check(CLI::IsMember({"wiener", "tikhonov", "tv", "tvqc", "rl"}))
        ->capture_default_str();
    cmd->add_option(
           "--model", o->model,
           "cyclic (circular convolution over one period, the paper) | linear (zero-padded "
           "convolution then crop: lensless captures, non-cyclic masks)")
        ->check(CLI::IsMember({"cyclic", "linear"}))
        ->capture_default_str();
    cmd->add_option(
           "--nsr", o->nsr,
           "Wiener noise-to-signal power ratio, dimensionless (>= 0); relative to |H|^2 of "
           "the PSF as normalised (sum 1: |H(0)| = 1)")
        ->capture_default_str();
    cmd->add_option("--lambda", o->lambda,
                    "Tikhonov / TV regularisation weight, dimensionless (>= 0)")
        ->capture_default_str();
    cmd->add_option("--regulariser", o->regulariser, "Tikhonov: identity | gradient")
        ->check(CLI::IsMember({"identity", "gradient"}))
        ->capture_default_str();
    auto* eps = cmd->add_option("--eps", o->eps, "TVQC: residual bound ||Ax - p||_2 <= EPS");
    auto* sigma = cmd->add_option("--noise-sigma", o->noise_sigma,
                                  "TVQC: per-pixel noise sigma (capture units) to derive EPS");
    eps->excludes(sigma);
    sigma->excludes(eps);
    cmd->add_flag("--nonneg", o->nonnegative, "TV / TVQC: constrain the estimate to x >= 0");
    cmd->add_option("--iters", o->iterations, "Iterative methods: maximum iterations")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    cmd->add_option("--tol", o->tolerance, "Iterative methods: stop at this relative change of x")
        ->capture_default_str();
    cmd->add_option("--downsample", o->downsample,
                    "K rounds of 2x2 box averaging of capture and PSF (factor 2^K per side)")
        ->check(CLI::Range(0, 12))
        ->capture_default_str();
    cmd->add_option("--background", o->background,
                    "none | corner (mean of the PSF's rows/cols 5..14, subtracted from PSF and "
                    "capture, as the DiffuserCam tutorial) | VALUE (counts, from the capture only)")
        ->capture_default_str();
    cmd->add_option("--normalize", o->normalize,
                    "none (PSF scaled to unit sum) | l2 (capture window and PSF each divided by "
                    "its L2 norm)")
        ->check(CLI::IsMember({"none", "l2"}))
        ->capture_default_str();
    cmd->add_option("-o,--output", o->output,
                    "Output image: .png (scaled, see below), .tif/.tiff or .npy (raw float32)")
        ->required();
    cmd->add_option("--bits", o->bits, "PNG bit depth: 8 | 16")
        ->check(CLI::IsMember({8, 16}))
        ->capture_default_str();
    cmd->add_option("--scale", o->scale,
                    "PNG scaling: max (1 / max over all channels) or a factor VALUE (> 0)")
        ->capture_default_str();
    cmd->add_option("--stats", o->stats,
                    "Stats JSON: per-stage times, iterations, objective, residual, period check");
    cmd->add_flag("--json", o->json, "Print the stats JSON on stdout instead of the summary");
    cmd->add_flag("--explain", o->explain,
                  "Say on stderr what each step decided (window, background, period check)");
    cmd->callback([o] { run_decode(*o); });
}

const Registration kDecode(50, "decode", setup);

}  // namespace
}  // namespace pinmask::cli
