#include "cli/options/decode_flags.hpp"

#include <cctype>
#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "decode/capture/estimate_output.hpp"
#include "decode/solvers/decode_modes.hpp"

namespace pinmask::cli {

const char* const kDecodeFooter = R"(
Steps: dark frame subtracted (same size, 1 or the capture's channels) -> --background ->
--downsample -> period check -> --crop -> --normalize -> decode each channel (RGB channels in
parallel threads) -> write.
Read from the data unless given (auto): --model (linear for a measured PSF that covers the
capture), --crop, --background (a measured PSF's dark floor), --method (tv for the linear model,
whose light from beyond the sensor is unknown; wiener for the cyclic model) and, for tv and tvqc, --nonneg (on for an intensity); --explain and
OUT.config.json ("chosen") say each choice and why.
Period: the PSF's size. The capture's own period is measured from its autocorrelation and a
mismatch is reported on stderr and in the stats (skipped, with the reason, when the capture
holds fewer than two periods along an axis).
Flags of one method only (--nsr, --nsr-map: wiener; --lambda: tikhonov, tv; --regulariser:
tikhonov; --eps, --noise-sigma: tvqc; --nonneg: tv, tvqc; --iters, --tol: tv, tvqc,
richardson-lucy) are refused with another method; --nsr and --nsr-map exclude each other.
NSR map (--nsr-map FILE): one NSR per frequency of the decoded working grid (the period, or the
padded frame with --model linear; after --downsample), full spectrum in fft2 order, read as
deconvwnr's array NSR. The robust design's decoder is this: `score MASK --robust SPEC
--robust-decoder DIR` writes DIR/robust-psf.tiff and DIR/robust-nsr.npy, then
`decode CAPTURE --psf DIR/robust-psf.npy --nsr-map DIR/robust-nsr.npy -o OUT`.
Precision: auto uses float32 (FFTW float) for every method from 256 x 256 decoded pixels on,
double below; a PSF whose values cancel beyond float32's range runs in double (auto, with a
note in --explain) or is refused (single).
Scale: every solver works on the capture divided by its largest magnitude and scales back, so
the result does not depend on the capture's units. A TVQC run that ends without meeting
||Ax - p||_2 <= eps still writes its estimate, exit 0, with a warning on stderr and
"constraint_met": false in the stats.
Output: PNG clips negatives to 0 and multiplies by 1/max over all channels (or by --scale),
then writes 8- or 16-bit; .tif/.tiff (float32) and .npy (float32) hold the raw estimate.
Orientation: the output is in the decoded window's pixel grid, never flipped or mirrored: row 0
is the window's top row, column 0 its left column; a capture identical to the PSF decodes to a
point at (row floor(H/2), column floor(W/2)), the PSF's centre (deconvwnr convention).
Units: with --normalize none the PSF is scaled to unit sum and the estimate is in capture
counts; with --normalize l2 both are divided by their L2 norms (the DiffuserCam tutorial).
Either way one factor serves every channel: a colour capture keeps its channels' ratios.
Also written: OUT.config.json (the resolved configuration) next to the output. In the stats,
everything but "timings_s" is the same, byte for byte, for the same inputs and options.
Ctrl-C (or SIGTERM) during tv, tvqc or richardson-lucy ends the iteration early: the estimate so
far is written as usual and marked "interrupted" in the stats; a second Ctrl-C kills at once.

Examples:
  pinmask decode capture.tiff --mask paper.mask.json --dark dark.tiff -o scene.png --stats s.json
  pinmask decode raw.tif --psf psf.tif --model linear --background corner --downsample 2 \
      --normalize l2 --crop none --method tv --lambda 1e-4 --iters 100 -o hand.png)";

namespace {

// A mode's names with "auto" first (--model).
std::vector<std::string> with_auto(std::vector<std::string> names) {
    names.insert(names.begin(), "auto");
    return names;
}

}  // namespace

DecodeFlags add_decode_flags(CLI::App& cmd, DecodeCommand& o) {
    DecodeFlags f;
    DecodeRequest& q = o.request;
    auto method_flag = [&](CLI::Option* opt, MethodParameter p) {
        f.method_flags.emplace_back(opt, p);
        return opt;
    };
    cmd.add_option("capture", o.capture,
                   "Capture image: TIFF (8/16-bit, float32), PNG (8/16-bit), .npy, JPEG, or camera "
                   "RAW by extension (.dng, .cr2, .nef, ...: see --bayer); grey or RGB (required "
                   "unless --batch)");
    auto* mask =
        cmd.add_option("--mask", o.mask, "Mask file (*.mask.json); its PSF is synthesised");
    auto* psf = cmd.add_option("--psf", o.psf,
                               "PSF file (float TIFF or .npy, with its sidecar when present)");
    mask->excludes(psf);
    psf->excludes(mask);
    cmd.add_option("--object-distance", o.object_distance,
                   "With --mask: decode with the PSF for an object at this distance (e.g. 2m, "
                   "inf; refocusing after capture): the integer torus when the pitch there is a "
                   "whole number of pixels (within 0.25 px across one period), else the "
                   "exact-geometry PSF at u over the whole frame (sets --model linear --crop "
                   "none)")
        ->needs(mask);
    cmd.add_option("--dark", o.dark,
                   "Dark frame (capture through an all-opaque film), subtracted first; same size");
    cmd.add_option("--crop", o.crop,
                   "Window decoded: auto (none for the linear model or a PSF that covers the "
                   "capture, else center), center (the period centred in the frame), none (whole "
                   "frame, PSF zero-padded), or X,Y (top-left column,row of one period)")
        ->capture_default_str();
    cmd.add_option("--method", o.method,
                   "auto (tv for the linear model, wiener for the cyclic; a flag only one of them "
                   "reads chooses it: --nsr, --nsr-map wiener, "
                   "--lambda, --nonneg, --iters, --tol tv) | wiener (closed form, deconvwnr) | "
                   "tikhonov (closed form) | tv (TV-L2, ADMM) | tvqc (min TV s.t. ||Ax - p||_2 "
                   "<= eps) | richardson-lucy")
        ->capture_default_str();
    cmd.add_option("--model", o.model,
                   "auto (linear for a measured PSF that covers the capture, a lensless camera's; "
                   "cyclic otherwise) | cyclic (circular convolution over one period, the paper) | "
                   "linear (zero-padded convolution then crop: lensless captures, non-cyclic "
                   "masks)")
        ->check(CLI::IsMember(with_auto(name_list(kConvModelNames))))
        ->capture_default_str();
    method_flag(cmd.add_option("--nsr", o.nsr,
                               "wiener: noise-to-signal power ratio, dimensionless (>= 0); "
                               "relative to |H|^2 of the PSF as normalised (sum 1: |H(0)| = 1); "
                               "auto: the NSR of least expected error for the noise and scene "
                               "spectrum read from the capture (docs/decoding.md)")
                    ->capture_default_str(),
                MethodParameter::kNsr);
    cmd.add_option("--nsr-map", o.nsr_map,
                   "wiener: per-frequency NSR instead of --nsr: a .npy or float TIFF of the "
                   "working grid's full spectrum (fft2 layout: row k, column l is frequency "
                   "(k/R, l/C)), finite, >= 0, same units as --nsr (e.g. score --robust-decoder's "
                   "robust-nsr.npy)");
    method_flag(cmd.add_option("--lambda", o.lambda,
                               "tikhonov (> 0, dimensionless) / tv (>= 0, capture units) "
                               "regularisation weight; auto (tikhonov): chosen from the capture "
                               "as for --nsr auto")
                    ->capture_default_str(),
                MethodParameter::kLambda);
    method_flag(cmd.add_option("--regulariser", o.regulariser, "tikhonov: identity | gradient")
                    ->check(CLI::IsMember(name_list(kRegulariserNames)))
                    ->capture_default_str(),
                MethodParameter::kRegulariser);
    auto* eps = method_flag(
        cmd.add_option("--eps", q.eps, "tvqc: residual bound ||Ax - p||_2 <= EPS (capture units)"),
        MethodParameter::kEps);
    auto* sigma = method_flag(cmd.add_option("--noise-sigma", q.noise_sigma,
                                             "tvqc: per-pixel noise sigma (capture units) to "
                                             "derive EPS"),
                              MethodParameter::kNoiseSigma);
    eps->excludes(sigma);
    sigma->excludes(eps);
    auto* nonneg = method_flag(cmd.add_flag("--nonneg", q.nonnegative,
                                            "tv / tvqc: constrain x >= 0 (default: when the "
                                            "capture is an intensity, read from it)"),
                               MethodParameter::kNonnegative);
    auto* no_nonneg =
        method_flag(cmd.add_flag("--no-nonneg", o.no_nonneg, "tv / tvqc: do not constrain x >= 0"),
                    MethodParameter::kNonnegative);
    nonneg->excludes(no_nonneg);
    no_nonneg->excludes(nonneg);
    method_flag(cmd.add_option("--iters", q.iterations,
                               "tv, tvqc, richardson-lucy: maximum iterations (>= 1)")
                    ->check(CLI::Range(1, 2147483647))
                    ->capture_default_str(),
                MethodParameter::kIterations);
    method_flag(cmd.add_option("--tol", q.tolerance,
                               "tv, tvqc, richardson-lucy: stop at this relative change of x")
                    ->capture_default_str(),
                MethodParameter::kTolerance);
    cmd.add_option("--downsample", q.downsample,
                   "K rounds of 2x2 box averaging of capture and PSF (factor 2^K per side)")
        ->check(CLI::Range(0, 12))
        ->capture_default_str();
    cmd.add_option("--background", o.background,
                   "auto (a measured PSF's dark floor, its 5 % quantile, off the PSF, and off "
                   "the capture too when both are whole counts; nothing for a mask's PSF) | "
                   "none | corner (mean of the PSF's rows/cols 5..14, subtracted from PSF and "
                   "capture, as the DiffuserCam tutorial) | VALUE (counts, from the capture only; "
                   "|VALUE| <= the capture's largest magnitude)")
        ->capture_default_str();
    cmd.add_option("--normalize", o.normalize,
                   "none (PSF scaled to unit sum) | l2 (capture window and PSF each divided by "
                   "its L2 norm, one factor over the channels)")
        ->check(CLI::IsMember(name_list(kNormalizeModeNames)))
        ->capture_default_str();
    cmd.add_option("--precision", o.precision,
                   "auto (float32 from 256 x 256 decoded pixels, every method) | single | "
                   "double")
        ->check(CLI::IsMember(name_list(kPrecisionNames)))
        ->capture_default_str();
    cmd.add_option(
           "--threads", q.threads,
           "FFTW threads for transforms of >= 512 x 512 (0: all cores); channels "
           "always decode in parallel. With PINMASK_WISDOM=off the bytes do not depend on it; with "
           "the wisdom cache FFTW measures a plan per thread count, and float32 results "
           "can differ in the last bits (about 1e-6 relative) between counts (recorded "
           "in the config)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    cmd.add_option("-o,--output", o.output,
                   "Output image: .png (scaled, see below), .tif/.tiff or .npy (raw float32)")
        ->required();
    cmd.add_option("--bits", o.bits, "PNG bit depth: 8 | 16")
        ->check(CLI::IsMember({8, 16}))
        ->capture_default_str();
    cmd.add_option("--scale", o.scale,
                   "PNG scaling: max (1 / max over all channels) or a factor VALUE (> 0)")
        ->capture_default_str();
    cmd.add_option("--stats", o.stats,
                   "Stats JSON: iterations, objective, residual, period check; wall-clock "
                   "figures only under \"timings_s\"");
    cmd.add_flag("--json", o.json, "Print the stats JSON on stdout instead of the summary");
    cmd.add_flag("--explain", o.explain,
                 "Say on stderr what each step decided (window, background, period check, "
                 "precision, threads, FFT planning time)");
    cmd.add_flag("--quiet", o.quiet,
                 "No progress lines on stderr (an iterative decode that runs over 2 s reports "
                 "its iterations and the time left) and no advice on a method or weight the "
                 "capture makes poor (the stats keep it under \"warnings\")");
    return f;
}

namespace {

// --nsr / --lambda: "auto" or a number (its range is the library's to refuse).
double parse_weight(const std::string& text, const char* flag, bool& automatic) {
    automatic = text == "auto";
    if (automatic) return 0.0;
    try {
        return parse_number(text, flag);
    } catch (const InvalidInput&) {
        throw invalid_field(flag, text, "must be a finite number or auto");
    }
}

}  // namespace

void resolve_method(DecodeCommand& c, const DecodeFlags& flags) {
    c.request.nsr = parse_weight(c.nsr, "--nsr", c.request.nsr_auto);
    c.request.lambda = parse_weight(c.lambda, "--lambda", c.request.lambda_auto);
    std::vector<GivenParameter> given;
    for (const auto& [opt, parameter] : flags.method_flags) {
        if (opt->count() == 0) continue;
        given.push_back({parameter, opt->as<std::string>()});
        if (parameter == MethodParameter::kNsr && !c.nsr_map.empty()) {
            throw invalid_field("--nsr", opt->as<std::string>(),
                                "conflicts with --nsr-map " + c.nsr_map +
                                    " (the map replaces the scalar NSR); give one of them");
        }
    }
    const std::optional<DecodeMethod> method = parse_decode_method_or_auto(c.method, "--method");
    c.request.method_auto = !method;
    if (method) c.request.method = *method;
    // Method auto: a given flag that only wiener or only tv reads says which.
    resolve_implied_method(c.request, given, !c.nsr_map.empty());
    // A per-frequency NSR map replaces the scalar NSR, automatic or given (a given --nsr is
    // refused above).
    if (!c.nsr_map.empty()) c.request.nsr_auto = false;
    if (!c.nsr_map.empty() && c.request.method != DecodeMethod::kWiener) {
        throw invalid_field("--nsr-map", c.nsr_map,
                            "is not used by --method " +
                                std::string(decode_method_name(c.request.method)) +
                                " (only by wiener); remove it or choose that method");
    }
    refuse_unused_parameters(c.request, given);
}

void resolve_request(DecodeCommand& c) {
    DecodeRequest& q = c.request;
    q.crop_auto = c.crop == "auto";
    if (!q.crop_auto) q.crop = parse_crop(c.crop);
    q.background = parse_background(c.background);
    q.normalize = parse_normalize_mode(c.normalize, "--normalize");
    q.model_auto = c.model == "auto";
    if (!q.model_auto) q.model = parse_conv_model(c.model, "--model");
    // --nonneg or --no-nonneg given: that; neither: read from the capture.
    q.nonnegative_auto = !q.nonnegative && !c.no_nonneg;
    q.regulariser = parse_regulariser(c.regulariser, "--regulariser");
    q.precision = parse_precision(c.precision, "--precision");
}

CropSpec parse_crop(const std::string& s) {
    if (s == "center" || s == "centre") return {CropMode::kCenter};
    if (s == "none") return {CropMode::kNone};
    const auto comma = s.find(',');
    if (comma != std::string::npos) {
        const double x = parse_number(s.substr(0, comma), "--crop X");
        const double y = parse_number(s.substr(comma + 1), "--crop Y");
        // Range first: casting a double outside int's range is undefined behaviour.
        const auto whole = [](double v) { return std::fabs(v) <= 1e9 && v == std::floor(v); };
        if (whole(x) && whole(y))
            return {CropMode::kCorner, static_cast<int>(y), static_cast<int>(x)};
    }
    throw invalid_field("--crop", s, "must be center, none or X,Y (integer pixel corner)");
}

DecodeBackground parse_background(const std::string& s) {
    for (const auto& [mode, name] : kBackgroundModeNames)
        if (mode != BackgroundMode::kValue && s == name) return {mode, 0.0};
    return {BackgroundMode::kValue, parse_number(s, "--background")};
}

std::optional<double> parse_scale(const std::string& s) {
    if (s == "max") return std::nullopt;
    const double v = parse_number(s, "--scale");
    if (!(v > 0.0)) throw invalid_field("--scale", s, "must be max or a factor > 0");
    return v;
}

void refuse_ignored_output_flags(const CLI::App& cmd, const DecodeCommand& o, bool batch,
                                 const std::string& batch_format) {
    const auto given = [&](const char* flag) { return cmd.count(flag) > 0; };
    const auto value = [&](const char* flag) { return cmd.get_option(flag)->as<std::string>(); };
    for (const char* flag : {"--batch-format", "--batch-stats"})
        if (!batch && given(flag))
            throw invalid_field(flag, value(flag),
                                "is used with --batch only; remove it or give --batch");
    std::string format = batch_format;
    for (char& c : format) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!batch && o.output.empty()) return;  // refused as missing later
    const bool png = batch ? format == "png" : output_kind(o.output) == OutputKind::kPng;
    for (const char* flag : {"--bits", "--scale"})
        if (!png && given(flag))
            throw invalid_field(flag, value(flag),
                                "is used by .png output only (.tif/.tiff and .npy hold the raw "
                                "float32 estimate); remove it or write .png");
}

}  // namespace pinmask::cli
