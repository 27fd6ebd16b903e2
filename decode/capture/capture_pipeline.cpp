#include "decode/capture/capture_pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "core/units/number_format.hpp"
#include "decode/capture/capture_defaults.hpp"
#include "decode/capture/preprocess.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/decode_modes.hpp"
#include "decode/solvers/noise_estimate.hpp"
#include "decode/solvers/precision.hpp"

namespace pinmask {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string size_text(const Image& img) {
    return std::to_string(img.cols()) + " x " + std::to_string(img.rows()) + " x " +
           std::to_string(img.n_channels());
}

// background auto: a measured PSF's floor off the PSF, and off the capture too when both are
// counts (whole numbers: the same camera's units); nothing for a mask's PSF.
// `counts`: the PSF file's own values when the caller kept them (a PSF file is read scaled).
ChosenSetting auto_background(Image& capture, Image& psf, const std::optional<Plane>& psf_counts,
                              bool psf_one_period, CaptureDecodeSummary& s) {
    if (psf_one_period)
        return {"background", "none", "the PSF is a mask's, with no camera background"};
    const Plane& given = psf_counts ? *psf_counts : psf.channels.front();
    if (!psf_covers_capture(capture.rows(), capture.cols(), given.rows(), given.cols()))
        return {"background", "none",
                "the PSF is smaller than the capture: one period of a tiling, not a camera's "
                "response over its sensor"};
    if (!whole_numbers(given))
        return {"background", "none",
                "the PSF is not in whole counts (a computed or rescaled PSF): no camera floor "
                "to read"};
    if (psf_counts) psf.channels.assign(1, *psf_counts);
    double floor = 0.0;
    for (const Plane& p : psf.channels) floor = std::max(floor, psf_floor(p));
    if (!(floor > 0.0))
        return {"background", "none", "the PSF's 5 % quantile is 0: no dark floor to take off"};
    double peak = 0.0;
    for (const Plane& p : psf.channels) peak = std::max(peak, p.maxCoeff());
    if (floor >= kPsfFloorMaxOfPeak * peak)
        return {"background", "none",
                "the PSF's 5 % quantile " + format_number(floor, 6) +
                    " is at least a tenth of its peak: light, not a dark floor"};
    const bool counts = whole_numbers(capture);
    for (Plane& p : psf.channels) p -= floor;
    for (const Plane& p : psf.channels) check_psf(p, "PSF after its dark floor");
    s.psf_background = floor;
    if (counts) {
        for (Plane& p : capture.channels) p -= floor;
        s.background = floor;
    }
    return {"background", format_number(floor, 6),
            "the PSF's 5 % quantile, its dark floor, taken off the PSF" +
                std::string(counts ? " and the capture (both in counts)"
                                   : " only (the capture is not in the PSF's counts)")};
}

}  // namespace

void CaptureDecodeOptions::validate() const {
    if (downsample < 0 || downsample > 12)
        throw invalid_field("downsample", std::to_string(downsample), "must be 0..12");
    if (threads < 0 || threads > 1024)
        throw invalid_field("threads", std::to_string(threads), "must be 1..1024 (0: all cores)");
    if (background == BackgroundMode::kValue && !std::isfinite(background_value))
        throw invalid_field("background", format_number(background_value), "must be finite");
    // Method auto validates the options of both methods it may choose.
    for (DecodeMethod m : method_auto
                              ? std::vector<DecodeMethod>{DecodeMethod::kWiener, DecodeMethod::kTv}
                              : std::vector<DecodeMethod>{decode.method}) {
        DecodeOptions d = decode;
        d.method = m;
        d.validate();
        if (is_iterative(m) && d.iterative.max_iterations < 1)
            throw invalid_field("iterations", std::to_string(d.iterative.max_iterations),
                                "must be >= 1 (0 iterations would return the starting point)");
    }
}

PreparedCapture prepare_capture(CaptureDecodeInputs in, const CaptureDecodeOptions& o) {
    o.validate();
    PreparedCapture out;
    CaptureDecodeSummary& s = out.summary;
    Image& capture = in.capture;
    Image& psf = in.psf;
    check_image_finite(capture, "capture");
    if (psf.empty()) throw invalid_field("psf", "empty", "needs at least one pixel");
    for (const Plane& p : psf.channels) check_psf(p, "PSF");

    auto t0 = Clock::now();
    if (in.dark) {
        check_image_finite(*in.dark, "dark frame");
        capture = subtract_dark(capture, *in.dark);
    }
    s.seconds.dark = seconds_since(t0);

    // Background: a value off the capture, or the tutorial's corner patch off PSF and capture,
    // or (auto) a measured PSF's floor (decode/capture/capture_defaults.hpp).
    t0 = Clock::now();
    if (o.background == BackgroundMode::kAuto) {
        s.chosen.push_back(auto_background(capture, psf, in.psf_counts, in.psf_one_period, s));
    } else if (o.background != BackgroundMode::kNone) {
        double b = o.background_value;
        if (o.background == BackgroundMode::kCorner) {
            if (!in.psf_counts) {
                throw invalid_field("background", "corner",
                                    "needs a measured PSF: a PSF synthesised from a mask has no "
                                    "camera background");
            }
            b = corner_background(*in.psf_counts);
            psf.channels.assign(1, *in.psf_counts - b);
        } else {
            double peak = 0.0;
            for (const Plane& p : capture.channels) peak = std::max(peak, p.abs().maxCoeff());
            if (std::abs(b) > peak) {
                throw invalid_field("background", format_number(b),
                                    "must not exceed the capture's largest magnitude " +
                                        format_number(peak) + " counts (it would leave no scene)");
            }
        }
        for (Plane& p : capture.channels) p -= b;
        s.background = b;
        s.notes.push_back("background " + format_number(b) + " subtracted from the capture" +
                          (o.background == BackgroundMode::kCorner
                               ? " and the PSF (mean of the PSF's rows/cols 5..14)"
                               : ""));
    }
    // Downsampled: each channel's noise is measured before, where the scene's texture reaches
    // the finest scale least (a diffuser's caustics fill it after a few rounds: the hand's
    // estimate is 36 counts at full size and 39 after two rounds, where independent pixel noise
    // would be 9), and carried through the rounds: a 2 x 2 mean halves the sigma of
    // independent pixel noise.
    std::vector<double> noise_sigmas;
    if (o.downsample > 0) {  // box_downsample copies even for 0 rounds
        for (const Plane& p : capture.channels)
            noise_sigmas.push_back(std::ldexp(estimate_noise_sigma(p), -o.downsample));
        for (Plane& p : capture.channels) p = box_downsample(p, o.downsample);
        for (Plane& p : psf.channels) p = box_downsample(p, o.downsample);
    }
    if (o.downsample > 0 || o.background == BackgroundMode::kCorner) {
        for (const Plane& p : psf.channels) check_psf(p, "PSF after preprocessing");
    }
    s.seconds.preprocess = seconds_since(t0);
    if (o.downsample > 0)
        s.notes.push_back("downsampled " + std::to_string(o.downsample) +
                          " rounds of 2x2: capture " + size_text(capture) + ", PSF " +
                          size_text(psf));

    // The model and the crop read from the sizes and the PSF's kind.
    DecodeOptions d = o.decode;
    CropSpec crop_spec = o.crop;
    const bool covers = psf_covers_capture(capture.rows(), capture.cols(), psf.rows(), psf.cols());
    if (o.model_auto) {
        d.model = covers && !in.psf_one_period ? ConvModel::kLinear : ConvModel::kCyclic;
        s.chosen.push_back(
            {"model", conv_model_name(d.model),
             !covers ? "the PSF " + size_text(psf) + " is smaller than the capture " +
                           size_text(capture) + ": one period of a cyclic tiling"
             : in.psf_one_period
                 ? "the PSF is one period of a mask's tiling (synthesised from the mask, or "
                   "a cyclic PSF file of pinmask's)"
                 : "the PSF " + size_text(psf) + " covers the capture " + size_text(capture) +
                       ": a camera's response over its sensor, not one period of a tiling"});
    }
    if (o.crop_auto) {
        const bool one_period = psf.rows() == capture.rows() && psf.cols() == capture.cols();
        const bool whole = d.model == ConvModel::kLinear || one_period;
        crop_spec = {whole ? CropMode::kNone : CropMode::kCenter};
        s.chosen.push_back(
            {"crop", whole ? "none" : "center",
             whole ? (d.model == ConvModel::kLinear ? "the linear model reads the whole sensor"
                                                    : "the capture is one period, the PSF's size")
                   : "the period centred in the frame"});
    }

    // Period check on the frame's luminance (strips of it, decode/capture/period.hpp), against the
    // PSF.
    t0 = Clock::now();
    s.period = check_period(capture, psf.rows(), psf.cols());
    s.seconds.period_check = seconds_since(t0);
    if (!s.period.rows.checked)
        s.notes.push_back("period check skipped along the rows: " + s.period.rows.skip_reason);
    if (!s.period.cols.checked)
        s.notes.push_back("period check skipped along the columns: " + s.period.cols.skip_reason);
    for (const auto& [a, name] : {std::pair{&s.period.rows, "rows"}, {&s.period.cols, "columns"}}) {
        if (!a->found || a->within_tolerance || !a->matches) continue;
        s.notes.push_back("period check along the " + std::string(name) +
                          ": the repeat is weak or " + "broad, measured " +
                          format_number(a->measured_px, 5) + " +- " +
                          format_number(a->uncertainty_px, 2) + " px for the PSF's " +
                          std::to_string(a->expected_px) + " px, not significantly different " +
                          "(t = " + format_number(a->significance, 2) + " < " +
                          format_number(kMismatchSignificance, 2) + "): consistent with the PSF");
    }

    t0 = Clock::now();
    s.window = crop_window(capture.rows(), capture.cols(), psf.rows(), psf.cols(), crop_spec);
    // The whole frame (crop none, or a frame of one period) is kept as it is, not copied.
    if (s.window.row != 0 || s.window.col != 0 || s.window.rows != capture.rows() ||
        s.window.cols != capture.cols())
        capture = crop(capture, s.window);
    s.seconds.crop = seconds_since(t0);
    s.notes.push_back("decoding the window " + std::to_string(s.window.cols) + " x " +
                      std::to_string(s.window.rows) + " at x=" + std::to_string(s.window.col) +
                      ", y=" + std::to_string(s.window.row));

    if (o.method_auto || !o.method_implied_by.empty()) {
        const bool linear = d.model == ConvModel::kLinear;
        if (o.method_auto)
            d.method = auto_method_is_tv(linear) ? DecodeMethod::kTv : DecodeMethod::kWiener;
        std::string reason;
        if (!o.method_implied_by.empty()) {
            reason = field_ref(o.method_implied_by) + " given: only " +
                     decode_method_name(d.method) + " of the automatic choice's wiener and tv " +
                     "reads it";
        } else if (d.method == DecodeMethod::kTv) {
            // Measured on the window decoded, after the background and the crop.
            reason =
                "the linear model: tv solves it with its crop exactly, wiener would read "
                "the light beyond the sensor as zero (the window's border band averages " +
                format_number(100 * border_fill(capture), 3) + " % of its mean)";
        } else {
            reason = "the cyclic model: the closed form is its exact least-error filter";
        }
        s.chosen.push_back({"method", decode_method_name(d.method), reason});
    }

    if (o.nonnegative_auto && (d.method == DecodeMethod::kTv || d.method == DecodeMethod::kTvqc)) {
        double low = 0.0, sigma = 0.0;
        const bool intensity = capture_is_intensity(capture, low, sigma);
        d.tv.nonnegative = d.tvqc.nonnegative = intensity;
        s.chosen.push_back(
            {"nonnegative", intensity ? "true" : "false",
             "the capture's 0.1 % quantile " + format_number(low, 4) +
                 (intensity ? " is at least" : " is below") + " -3 x its noise sigma " +
                 format_number(sigma, 4) +
                 (intensity ? ": an intensity" : ": not an intensity (signed values)")});
    }

    // One factor over the channels (decode/capture/preprocess.hpp channels_l2_norm): a colour
    // PSF keeps its channels' ratios, so the estimate's colour is the scene's.
    if (o.normalize == NormalizeMode::kL2) {
        const double capture_norm = channels_l2_norm(capture.channels, "capture window");
        for (Plane& p : capture.channels) {
            s.capture_l2_norms.push_back(capture_norm);
            p /= capture_norm;
        }
        for (double& sigma : noise_sigmas) sigma /= capture_norm;
        const double psf_norm = channels_l2_norm(psf.channels, "PSF");
        for (Plane& p : psf.channels) {
            s.psf_l2_norms.push_back(psf_norm);
            p /= psf_norm;
        }
    } else {
        const double psf_sum = channels_mean_sum(psf.channels, "PSF");
        for (Plane& p : psf.channels) {
            s.psf_sums.push_back(psf_sum);
            p /= psf_sum;
        }
    }
    for (const ChosenSetting& c : s.chosen)
        s.notes.push_back(field_ref(c.name) + " " + c.value + " (auto): " + c.reason);
    s.model = d.model;
    s.method = d.method;
    s.decoded_rows = capture.rows();
    s.decoded_cols = capture.cols();

    // Precision and threads.
    const long long pixels = static_cast<long long>(s.decoded_rows) * s.decoded_cols;
    const bool want_single =
        o.precision == Precision::kSingle ||
        (o.precision == Precision::kAuto && pixels >= kSinglePrecisionMinPixels);
    std::string float_problem;  // a PSF that float32 cannot hold (decode/solvers/precision.hpp)
    for (const Plane& p : psf.channels) {
        if (want_single && float_problem.empty()) float_problem = single_precision_problem(p);
    }
    if (!float_problem.empty()) {
        if (o.precision == Precision::kSingle)
            throw invalid_field("precision", "single", float_problem + "; use double or auto");
        s.notes.push_back("precision: double instead of float32: " + float_problem);
    }
    s.single_precision = want_single && float_problem.empty();
    d.single_precision = s.single_precision;
    if (o.threads > 0) {
        set_fft_threads(o.threads);
    } else {
        // Asked once per process: glibc reads it from sysfs on every call (2 % of a warm 256 x
        // 256 Wiener decode).
        static const int cores =
            static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        set_fft_threads(cores);
    }
    const ConvGeometry g =
        make_conv_geometry(d.model, s.decoded_rows, s.decoded_cols, psf.rows(), psf.cols());
    s.fft_threads = fft_threads_for(g.work_rows, g.work_cols);
    s.notes.push_back(std::string(decode_method_name(d.method)) + " in " +
                      (s.single_precision ? "single (float32)" : "double") + " precision on a " +
                      std::to_string(g.work_rows) + " x " + std::to_string(g.work_cols) +
                      " grid, " + std::to_string(s.fft_threads) + " FFT thread(s), " +
                      std::to_string(capture.n_channels()) + " channel(s) in parallel");

    out.capture = std::move(capture);
    out.psf = std::move(psf.channels);
    out.decode = std::move(d);
    out.noise_sigmas = std::move(noise_sigmas);
    return out;
}

CaptureDecodeResult decode_prepared(PreparedCapture prepared) {
    CaptureDecodeResult out;
    out.summary = std::move(prepared.summary);
    CaptureDecodeSummary& s = out.summary;
    const DecodeOptions& d = prepared.decode;
    const auto t0 = Clock::now();
    const double planning_before = fft_plan_stats().planning_seconds;
    const std::vector<double>& noise_sigmas = prepared.noise_sigmas;
    s.channels = decode_channels(prepared.capture, prepared.psf, d, noise_sigmas);
    s.seconds.decode = seconds_since(t0);
    s.seconds.fft_planning = fft_plan_stats().planning_seconds - planning_before;
    for (std::size_t ch = 0; ch < s.channels.size(); ++ch) {
        const std::optional<AutoWeight>& w = s.channels[ch].auto_weight;
        if (!w) continue;
        s.notes.push_back("channel " + std::to_string(ch) + ": " +
                          field_ref(d.method == DecodeMethod::kWiener ? "nsr" : "lambda") + " " +
                          format_number(w->weight, 4) + " chosen from the capture (noise sigma " +
                          format_number(w->noise_sigma, 4) +
                          (noise_sigmas.empty() ? "" : ", measured before downsampling") +
                          (d.method == DecodeMethod::kTv
                               ? std::string(")")
                               : ", scene spectrum |f|^-" + format_number(w->alpha, 3) + ")"));
    }
    for (const DecodeResult& r : s.channels)
        for (const std::string& w : r.warnings)
            if (std::find(s.warnings.begin(), s.warnings.end(), w) == s.warnings.end())
                s.warnings.push_back(w);
    for (DecodeResult& r : s.channels) {
        out.estimate.channels.push_back(std::move(r.image));
        r.image = Plane();
        s.interrupted = s.interrupted || r.interrupted;
        s.constraint_met = s.constraint_met && r.constraint_met;
    }
    // decode_plane refuses a non-finite estimate (RuntimeFailure), so every channel is finite.
    return out;
}

CaptureDecodeResult decode_capture(CaptureDecodeInputs in, const CaptureDecodeOptions& o) {
    return decode_prepared(prepare_capture(std::move(in), o));
}

}  // namespace pinmask
