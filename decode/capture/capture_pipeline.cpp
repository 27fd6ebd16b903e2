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
#include "decode/capture/preprocess.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/decode_method.hpp"
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

}  // namespace

void CaptureDecodeOptions::validate() const {
    if (downsample < 0 || downsample > 12)
        throw invalid_field("downsample", std::to_string(downsample), "must be 0..12");
    if (threads < 0 || threads > 1024)
        throw invalid_field("threads", std::to_string(threads), "must be 1..1024 (0: all cores)");
    if (background == BackgroundMode::kValue && !std::isfinite(background_value))
        throw invalid_field("background", format_number(background_value), "must be finite");
    decode.validate();
    if (is_iterative(decode.method) && decode.iterative.max_iterations < 1)
        throw invalid_field("iterations", std::to_string(decode.iterative.max_iterations),
                            "must be >= 1 (0 iterations would return the starting point)");
}

CaptureDecodeResult decode_capture(CaptureDecodeInputs in, const CaptureDecodeOptions& o) {
    o.validate();
    CaptureDecodeResult out;
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

    // Background: a value off the capture, or the tutorial's corner patch off PSF and capture.
    t0 = Clock::now();
    if (o.background != BackgroundMode::kNone) {
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
    if (o.downsample > 0) {  // box_downsample copies even for 0 rounds
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
    s.window = crop_window(capture.rows(), capture.cols(), psf.rows(), psf.cols(), o.crop);
    // The whole frame (crop none, or a frame of one period) is kept as it is, not copied.
    if (s.window.row != 0 || s.window.col != 0 || s.window.rows != capture.rows() ||
        s.window.cols != capture.cols())
        capture = crop(capture, s.window);
    s.seconds.crop = seconds_since(t0);
    s.notes.push_back("decoding the window " + std::to_string(s.window.cols) + " x " +
                      std::to_string(s.window.rows) + " at x=" + std::to_string(s.window.col) +
                      ", y=" + std::to_string(s.window.row));

    if (o.normalize == NormalizeMode::kL2) {
        for (Plane& p : capture.channels) {
            s.capture_l2_norms.push_back(p.matrix().norm());
            p = l2_normalized(p, "capture window");
        }
        for (Plane& p : psf.channels) {
            s.psf_l2_norms.push_back(p.matrix().norm());
            p = l2_normalized(p, "PSF");
        }
    } else {
        for (Plane& p : psf.channels) {
            s.psf_sums.push_back(p.sum());
            p /= s.psf_sums.back();
        }
    }
    s.decoded_rows = capture.rows();
    s.decoded_cols = capture.cols();

    // Precision and threads.
    DecodeOptions d = o.decode;
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

    t0 = Clock::now();
    const double planning_before = fft_plan_stats().planning_seconds;
    s.channels = decode_channels(capture, psf.channels, d);
    s.seconds.decode = seconds_since(t0);
    s.seconds.fft_planning = fft_plan_stats().planning_seconds - planning_before;
    for (std::size_t ch = 0; ch < s.channels.size(); ++ch) {
        const std::optional<AutoWeight>& w = s.channels[ch].auto_weight;
        if (!w) continue;
        s.notes.push_back("channel " + std::to_string(ch) + ": " +
                          field_ref(d.method == DecodeMethod::kWiener ? "nsr" : "lambda") + " " +
                          format_number(w->weight, 4) + " chosen from the capture (noise sigma " +
                          format_number(w->noise_sigma, 4) +
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

}  // namespace pinmask
