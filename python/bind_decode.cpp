// Decoding: decode() is `pinmask decode` on arrays, one call of decode/capture/capture_pipeline
// (decode_capture) with the options of the library's DecodeRequest
// (decode/capture/decode_request.hpp), filled from the keyword arguments: names, defaults, refusals
// and numbers are the CLI's; the messages name the keywords (python/keyword_names).
#include <atomic>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "decode/capture/capture.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/capture/decode_request.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/capture/period.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/decode_modes.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "python/background_arg.hpp"
#include "python/common.hpp"
#include "python/keyword_names.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

struct DecodeOutput {
    std::vector<DecodeResult> results;
    CropWindow window;
    PeriodCheck period;
    DecodeMethod method = DecodeMethod::kWiener;  // CaptureDecodeSummary::method
    std::vector<std::string> warnings;            // CaptureDecodeSummary::warnings
    std::vector<ChosenSetting> chosen;            // CaptureDecodeSummary::chosen
};

// The capture: a borrowed library plane (mono, no copy) or an owned image.
// (The PlaneArg that keeps a borrowed plane alive stays with the caller: Python references are
// never touched on the worker thread.)
struct CaptureArg {
    const Plane* plane = nullptr;
    Image image;
    int rows() const { return plane ? int(plane->rows()) : image.rows(); }
    int cols() const { return plane ? int(plane->cols()) : image.cols(); }
};

// `pinmask decode`'s library pipeline (decode/capture/capture_pipeline: dark frame, background,
// period check, crop, the automatic settings, PSF to unit sum, precision) with the CLI's own
// options (capture_decode_options), up to the decode: its method is then known. The pipeline
// owns its inputs: a borrowed capture or PSF is copied into it (a C++ copy, not a numpy
// conversion: input_copies() does not count it), a plane already converted from numpy is moved
// in.
PreparedCapture prepare_pipeline(CaptureArg& cap, PlaneArg& psf_in, bool measured_psf,
                                 const std::optional<Image>& dark,
                                 const CaptureDecodeOptions& options) {
    CaptureDecodeInputs in;
    in.capture = cap.plane ? Image(*cap.plane) : std::move(cap.image);
    // background="corner" reads the PSF's own values (a measured PSF, as the CLI's --psf file).
    if (measured_psf && options.background == BackgroundMode::kCorner) in.psf_counts = psf_in.get();
    in.psf = Image(psf_in.take());
    in.dark = dark;
    in.psf_one_period = !measured_psf;  // a mask's PSF
    return prepare_capture(std::move(in), options);
}

// The decode of a prepared capture (each channel), sorted for the result.
DecodeOutput decode_pipeline(PreparedCapture prepared) {
    CaptureDecodeResult res = decode_prepared(std::move(prepared));
    DecodeOutput out;
    out.window = res.summary.window;
    out.period = res.summary.period;
    out.method = res.summary.method;
    out.results = std::move(res.summary.channels);
    out.warnings = std::move(res.summary.warnings);
    out.chosen = std::move(res.summary.chosen);
    for (std::size_t i = 0; i < out.results.size() && i < res.estimate.channels.size(); ++i)
        out.results[i].image = std::move(res.estimate.channels[i]);
    return out;
}

// Closed-form decodes of at most this many capture values (all channels) run inline (see the
// decode binding).
constexpr Eigen::Index kInlineDecodePixels = Eigen::Index{1} << 22;

py::dict period_dict(const PeriodCheck& p) {
    auto axis = [](const AxisPeriodCheck& a) {
        py::dict d;
        d["size_px"] = a.size_px;
        d["expected_px"] = a.expected_px;
        d["checked"] = a.checked;
        d["skip_reason"] = a.skip_reason;
        d["found"] = a.found;
        d["measured_px"] = a.measured_px;
        d["peak_value"] = a.peak_value;
        d["peak_rise"] = a.peak_rise;
        d["early_exit"] = a.early_exit;
        d["within_tolerance"] = a.within_tolerance;
        d["high_pass_px"] = a.high_pass_px;
        d["uncertainty_px"] = a.uncertainty_px;
        d["significance"] = a.significance;
        d["matches"] = a.matches;
        return d;
    };
    py::dict d;
    d["rows"] = axis(p.rows);
    d["cols"] = axis(p.cols);
    d["tolerance_px"] = p.tolerance_px;
    d["checked"] = p.checked();
    d["matches"] = p.matches();
    return d;
}

// The method's own arguments as given: None means "not given" (the request's default).
struct MethodArgs {
    std::optional<double> nsr, lambda, eps, noise_sigma, tol;
    bool nsr_auto = false, lambda_auto = false;  // nsr / lambda_ given as "auto"
    std::optional<std::string> regulariser;
    std::optional<bool> nonneg;
    std::optional<int> iters;
};

// A given argument's value as Python writes it (for the refusal's message).
std::string python_text(const py::object& value) { return py::repr(value).cast<std::string>(); }

// nsr / lambda_: None (not given), a number, or "auto" (sets `automatic`; the value is then 0).
std::optional<double> weight_arg(const py::object& v, const char* name, bool& automatic) {
    automatic = false;
    if (v.is_none()) return std::nullopt;
    if (py::isinstance<py::str>(v)) {
        if (v.cast<std::string>() != "auto")
            throw invalid_field(field_ref(name), python_text(v), "must be a number or 'auto'");
        automatic = true;
        return 0.0;
    }
    const auto refuse = [&] {
        return py::type_error(py_names::spell_keywords(field_ref(name)) +
                              " must be a number or 'auto', not " +
                              std::string(py::str(v.get_type().attr("__name__"))));
    };
    if (py::isinstance<py::bool_>(v)) throw refuse();
    try {
        return py::float_(v).cast<double>();  // any real number (numpy scalars too)
    } catch (const py::error_already_set&) {
        throw refuse();
    }
}

// Writes the given method arguments into `r` (the others keep the request's defaults) and lists
// them, so that refuse_unused_parameters refuses one the method does not read, as the CLI
// refuses its flags.
std::vector<GivenParameter> set_method_args(DecodeRequest& r, const MethodArgs& a) {
    std::vector<GivenParameter> given;
    const auto give = [&](MethodParameter p, const py::object& v) {
        given.push_back({p, python_text(v)});
    };
    const auto weight = [](double v, bool automatic) -> py::object {
        if (automatic) return py::str("auto");
        return py::float_(v);
    };
    if (a.nsr) r.nsr_auto = a.nsr_auto;  // not given: the request's default (auto)
    if (a.lambda) r.lambda_auto = a.lambda_auto;
    if (a.nsr) give(MethodParameter::kNsr, weight(r.nsr = *a.nsr, a.nsr_auto));
    if (a.lambda) give(MethodParameter::kLambda, weight(r.lambda = *a.lambda, a.lambda_auto));
    if (a.regulariser) {
        r.regulariser = parse_regulariser(*a.regulariser, field_ref("regulariser"));
        give(MethodParameter::kRegulariser, py::str(*a.regulariser));
    }
    if (a.eps) give(MethodParameter::kEps, py::float_(*a.eps));
    if (a.noise_sigma) give(MethodParameter::kNoiseSigma, py::float_(*a.noise_sigma));
    r.eps = a.eps;
    r.noise_sigma = a.noise_sigma;
    if (a.nonneg) give(MethodParameter::kNonnegative, py::bool_(r.nonnegative = *a.nonneg));
    if (a.iters) give(MethodParameter::kIterations, py::int_(r.iterations = *a.iters));
    if (a.tol) give(MethodParameter::kTolerance, py::float_(r.tolerance = *a.tol));
    if (r.iterations < 1)
        throw invalid_field(field_ref("iterations"), std::to_string(r.iterations), "must be >= 1");
    if (a.eps && a.noise_sigma)
        throw InvalidInput(field_ref("eps") + " excludes " + field_ref("noise_sigma") +
                           " (give one of them)");
    return given;
}

// crop=: "center" (or "centre") | "none" | (row, col) of the period's top-left pixel.
CropSpec crop_arg(const py::handle& crop) {
    if (py::isinstance<py::str>(crop)) {
        const std::string s = crop.cast<std::string>();
        if (s == "center" || s == "centre") return {CropMode::kCenter};
        if (s == "none") return {CropMode::kNone};
        throw invalid_field(field_ref("crop"), s,
                            "must be center, none or (row, col) (integer pixel corner)");
    }
    const auto [row, col] = crop.cast<std::pair<int, int>>();
    return {CropMode::kCorner, row, col};
}

}  // namespace

void bind_decode(py::module_& m) {
    const DecodeRequest defaults;  // the keywords' defaults (tests/python/test_parity_defaults.py)
    m.def(
        "decode",
        [](const py::handle& capture, const py::handle& psf, const py::handle& mask,
           const std::string& method, const std::string& model, const py::object& nsr_arg,
           const py::object& lambda_arg, std::optional<std::string> regulariser,
           std::optional<double> eps, std::optional<double> noise_sigma, std::optional<bool> nonneg,
           std::optional<int> iters, std::optional<double> tol, const py::handle& crop,
           const py::handle& dark, const py::handle& background, int downsample,
           const std::string& normalize, const std::string& precision, int threads,
           const py::object& progress, double poll_s, const py::handle& nsr_map,
           const py::object& object_distance) {
            DecodeRequest r;
            r.model_auto = model == "auto";
            if (!r.model_auto) r.model = parse_conv_model(model, field_ref("model"));
            MethodArgs args{{},    {},    eps,         noise_sigma, tol,
                            false, false, regulariser, nonneg,      iters};
            args.nsr = weight_arg(nsr_arg, "nsr", args.nsr_auto);
            args.lambda = weight_arg(lambda_arg, "lambda", args.lambda_auto);
            const std::optional<double> nsr = args.nsr;
            const std::vector<GivenParameter> given = set_method_args(r, args);
            r.normalize = parse_normalize_mode(normalize, field_ref("normalize"));
            if (threads < 0 || threads > 1024)
                throw invalid_field(field_ref("threads"), std::to_string(threads),
                                    "must be 1..1024 (0: all cores)");
            r.threads = threads;
            r.background = background_arg(background);
            r.downsample = downsample;
            const std::optional<DecodeMethod> given_method =
                parse_decode_method_or_auto(method, field_ref("method"));
            r.method_auto = !given_method;
            if (given_method) r.method = *given_method;
            // Method auto: a keyword only wiener or only tv reads says which.
            resolve_implied_method(r, given, !nsr_map.is_none());
            refuse_unused_parameters(r, given);
            r.crop_auto = py::isinstance<py::str>(crop) && crop.cast<std::string>() == "auto";
            if (!r.crop_auto) r.crop = crop_arg(crop);
            r.nonnegative_auto = !nonneg.has_value();
            r.precision = parse_precision(precision, field_ref("precision"));
            if (psf.is_none() == mask.is_none())
                throw InvalidInput(
                    "decode needs the PSF: give psf= an array or mask= a Mask or path, not "
                    "both");
            CaptureArg cap;
            std::optional<PlaneArg> borrowed_capture;
            if (is_library_buffer(capture)) {
                borrowed_capture = plane_arg(capture, "capture");
                cap.plane = &borrowed_capture->get();
            } else {
                cap.image = image_arg(capture, "capture");
            }
            std::optional<PlaneArg> psf_arg;
            py::object refocus_info = py::none();
            if (!object_distance.is_none() && mask.is_none())
                throw invalid_field(field_ref("object_distance"),
                                    std::string(py::str(object_distance)),
                                    "refocuses the PSF synthesised from mask=: give mask=, not a "
                                    "measured psf=");
            if (!psf.is_none()) {
                psf_arg = plane_arg(psf, "psf");
            } else {
                Mask mk = mask_arg(mask);
                Plane p;
                if (object_distance.is_none()) {
                    py::gil_scoped_release release;
                    p = mask_psf(mk);
                } else {
                    // `decode --mask M --object-distance U` (cli/options/decode_inputs): the PSF
                    // of an object at u. A whole pitch there: the mask's PSF at that many pixels
                    // per cell; otherwise the exact-geometry PSF over the frame, decoded with the
                    // linear model and no crop (the command line switches the same way).
                    const double u = length_value(object_distance, "object_distance", true);
                    check_object_distance(mk.camera, u, "object_distance");
                    const RefocusGeometry g = refocus_geometry(mk, u);
                    if (g.exact_geometry) {
                        r.model = ConvModel::kLinear;
                        r.model_auto = false;
                        r.crop = {CropMode::kNone};
                        r.crop_auto = false;
                        ExactPsfOptions eo;
                        eo.object_distance_m = u;
                        eo.rows = cap.rows();
                        eo.cols = cap.cols();
                        py::gil_scoped_release release;
                        p = exact_psf(mk, eo);
                    } else {
                        mk = mask_at_distance(mk, u);
                        py::gil_scoped_release release;
                        p = mask_psf(mk);
                    }
                    py::dict info;  // the keys of the command's stats "psf"."refocus"
                    info["object_distance_m"] = u;
                    info["pitch_px"] = g.pitch_px;
                    info["whole_pixels_per_cell"] = g.whole_px;
                    info["mismatch_px"] = g.mismatch_px;
                    info["geometry"] = g.exact_geometry ? "exact" : "integer";
                    refocus_info = info;
                }
                psf_arg = plane_arg(to_array(std::move(p)), "psf");
            }
            std::optional<Image> dark_img;
            if (!dark.is_none()) dark_img = image_arg(dark, "dark");
            if (!nsr_map.is_none()) r.nsr_auto = false;  // the map replaces the scalar NSR
            CaptureDecodeOptions options = capture_decode_options(r);
            if (!nsr_map.is_none()) {
                // `decode --nsr-map`: a per-frequency NSR on the working grid (Wiener only, in
                // place of the scalar nsr); its size and values are checked by the decoder
                // (wiener.nsr_per_frequency).
                if (r.method != DecodeMethod::kWiener)
                    throw invalid_field(field_ref("nsr_map"), method,
                                        "is read by method wiener only");
                if (nsr)
                    throw InvalidInput(field_ref("nsr_map") + " excludes " + field_ref("nsr") +
                                       " (the map replaces the scalar NSR)");
                options.decode.wiener.nsr_per_frequency = plane_arg(nsr_map, "nsr_map").get();
            }
            options.decode.iterative.record_history = true;  // the result's history array
            options.validate();
            if (options.background == BackgroundMode::kCorner && psf.is_none()) {
                throw invalid_field(field_ref("background"), "corner",
                                    "needs a measured PSF (psf=): a PSF synthesised from a mask "
                                    "has no camera background");
            }

            // Everything before the decode (GIL released), so that the method that runs, given
            // or chosen from the capture, decides the progress and the thread below.
            PreparedCapture prepared;
            {
                py::gil_scoped_release release;
                prepared = prepare_pipeline(cap, *psf_arg, !psf.is_none(), dark_img, options);
            }
            DecodeOptions& run_options = prepared.decode;
            std::atomic<bool> stop{false};
            run_options.iterative.stop = &stop;
            // Iterations finished over all channels (the solvers count them): progress gets
            // the iteration each channel has reached.
            std::atomic<long long> iterations_done{0};
            run_options.iterative.iterations_done = &iterations_done;
            const auto channel_count =
                std::max<long long>(1, static_cast<long long>(prepared.capture.channels.size()));
            const bool iterative = is_iterative(run_options.method);
            const int max_iterations = iterative ? run_options.iterative.max_iterations : 0;
            DecodeOutput out;
            const auto work = [&] { out = decode_pipeline(std::move(prepared)); };
            // A closed-form decode without a progress callback runs on this thread (GIL
            // released): it takes milliseconds up to kInlineDecodePixels, and a worker thread's
            // start and fresh stack and heap pages cost ~0.1 ms, a third of a warm 128 x 128
            // Wiener decode. Ctrl-C is then seen when it returns.
            const Eigen::Index pixels =
                prepared.capture.channels.empty()
                    ? Eigen::Index{0}
                    : prepared.capture.channels[0].size() *
                          static_cast<Eigen::Index>(prepared.capture.channels.size());
            Poll poll = Poll::kContinue;
            if (!iterative && progress.is_none() && pixels <= kInlineDecodePixels) {
                py::gil_scoped_release release;
                work();
            } else {
                poll = run_with_interrupt(work, stop, progress, poll_s, [&](double seconds) {
                    py::dict info;
                    info["iteration"] = iterations_done.load() / channel_count;
                    info["max_iterations"] = max_iterations;
                    info["seconds"] = seconds;
                    return py::object(info);
                });
            }

            py::dict d;
            Image estimate;
            py::list channels;
            bool any_interrupted = false;
            for (DecodeResult& res : out.results) {
                py::array_t<double> hist(
                    {static_cast<py::ssize_t>(res.history.size()), py::ssize_t{4}});
                auto h = hist.mutable_unchecked<2>();
                for (std::size_t i = 0; i < res.history.size(); ++i) {
                    const auto k = static_cast<py::ssize_t>(i);
                    h(k, 0) = res.history[i].iteration;
                    h(k, 1) = res.history[i].seconds;
                    h(k, 2) = res.history[i].objective;
                    h(k, 3) = res.history[i].residual;
                }
                py::dict c;
                c["iterations"] = res.iterations;
                c["objective"] = res.objective;
                if (res.auto_weight) {
                    py::dict w;
                    w["weight"] = res.auto_weight->weight;
                    w["noise_sigma"] = res.auto_weight->noise_sigma;
                    w["scene_spectrum_exponent"] = res.auto_weight->alpha;
                    c["auto_weight"] = w;
                }
                c["residual"] = res.residual;
                c["converged"] = res.converged;
                c["interrupted"] = res.interrupted;
                c["seconds"] = res.seconds;
                c["history"] = hist;
                channels.append(c);
                any_interrupted = any_interrupted || res.interrupted;
                estimate.channels.push_back(std::move(res.image));
            }
            // Ctrl-C is Python's KeyboardInterrupt, as for any call; the solvers stopped at it.
            // (A progress callback returning False stops them and returns the estimate so far.)
            if (poll == Poll::kKeyboardInterrupt) raise_keyboard_interrupt();
            // Finite: decode_plane refuses a non-finite estimate (RuntimeFailure).
            d["image"] = image_to_array(std::move(estimate));
            d["channels"] = channels;
            d["interrupted"] = any_interrupted;
            d["window"] =
                py::make_tuple(out.window.row, out.window.col, out.window.rows, out.window.cols);
            d["period_check"] = period_dict(out.period);
            d["method"] = decode_method_name(out.method);  // given, or chosen (see chosen)
            if (!refocus_info.is_none()) d["refocus"] = refocus_info;
            // The settings read from the data: {name: {value, reason}}.
            py::dict chosen;
            for (const ChosenSetting& c : out.chosen) {
                py::dict e;
                e["value"] = c.value;
                e["reason"] = py_names::spell_keywords(c.reason);
                chosen[py::str(c.name)] = e;
            }
            d["chosen"] = chosen;
            // The CLI's "pinmask: warning:" lines, as Python warnings.
            for (const std::string& w : out.warnings) {
                const std::string text = "pinmask: " + py_names::spell_keywords(w);
                if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1) < 0)
                    throw py::error_already_set();
            }
            return as_result(d);
        },
        py::arg("capture"), py::arg("psf") = py::none(), py::arg("mask") = py::none(),
        py::arg("method") = defaults.method_auto ? "auto" : decode_method_name(defaults.method),
        py::arg("model") = "auto", py::arg("nsr") = py::none(), py::arg("lambda_") = py::none(),
        py::arg("regulariser") = py::none(), py::arg("eps") = py::none(),
        py::arg("noise_sigma") = py::none(), py::arg("nonneg") = py::none(),
        py::arg("iters") = py::none(), py::arg("tol") = py::none(), py::arg("crop") = "auto",
        py::arg("dark") = py::none(),
        py::arg("background") = background_mode_name(defaults.background.mode),
        py::arg("downsample") = defaults.downsample,
        py::arg("normalize") = normalize_mode_name(defaults.normalize),
        py::arg("precision") = precision_name(defaults.precision),
        py::arg("threads") = defaults.threads, py::arg("progress") = py::none(),
        py::arg("poll_s") = 0.05, py::arg("nsr_map") = py::none(),
        py::arg("object_distance") = py::none(),
        R"(Decodes a capture as `pinmask decode` does: dark frame subtracted, background,
downsampling, period check, crop, normalisation, each channel decoded (colour channels in
parallel). Same names, defaults, refusals and numbers as the CLI's flags.

capture: (rows, cols) or (rows, cols, channels) array, capture units. psf: a PSF array (any
sum > 0), or mask: a Mask or *.mask.json path (its PSF is synthesised).
method: 'auto' (tv for the linear model, where wiener would read the light beyond the sensor
as zero; wiener for the cyclic model; a keyword only one of them reads chooses it: nsr, nsr_map wiener; lambda_, nonneg,
iters, tol tv) | wiener (deconvwnr: PSF centre floor(size/2) at the origin, scalar nsr, real
part) | tikhonov (lambda_, regulariser identity|gradient) | tv (TV-L2 ADMM, lambda_) | tvqc (min
TV s.t. ||Ax - p||_2 <= eps, or eps from noise_sigma) | richardson-lucy. model: 'auto' (linear
for a psf= array that covers the capture, a lensless camera's response; cyclic for a smaller PSF
or mask=) | cyclic (circular convolution over one period) | linear (zero-padded, then cropped).
nonneg: x >= 0 for tv/tvqc (None: when the capture is an intensity, its 0.1 % quantile at least
-3 noise sigma). iters, tol: iterative methods (relative change of x). Method arguments left None take
the CLI's defaults (nsr 'auto', lambda_ 'auto', regulariser identity, nonneg False, iters
200, tol 1e-4); one given for a method that does not read it raises ValueError naming it and
the methods that do (as the CLI refuses --nsr with --method tv). nsr='auto' (wiener) and
lambda_='auto' (tikhonov: the weight of least expected error for the noise and scene spectrum
read from the capture; tv: a rule scaled by the noise and the PSF, docs/decoding.md) are the
defaults; each channel's auto_weight then says {weight, noise_sigma, scene_spectrum_exponent}. crop: 'auto' (none for the linear
model or a PSF covering the capture, else center) | 'center' | 'none' | (row, col) of the
period's top-left pixel. dark: dark frame, same size (1 or the capture's
channels). background: 'auto' (a psf= array's dark
floor, its 5 % quantile, off the PSF, and off the capture too when both hold whole counts) |
'none' | 'corner' (mean of the PSF's rows/cols 5..14, off PSF and capture; needs psf=) | a
number of counts off the capture. downsample: K rounds of 2x2 box
averaging of capture and PSF (0..12). normalize: 'none' (PSF to unit sum, estimate in capture
counts) | 'l2' (capture window and PSF each divided by its L2 norm, one factor over the
channels: a colour capture keeps its ratios). precision: 'auto' (float32
for every method from 256 x 256 decoded pixels) | 'single' | 'double'. threads: FFTW
threads for transforms of >= 512 x 512 (0: all cores; results do not depend on it).
nsr_map: wiener only, in place of nsr: a per-frequency NSR on the working grid (the decoded
window's size for the cyclic model), as `decode --nsr-map` reads it, e.g. the robust-nsr.npy
that `score --robust-decoder` writes beside robust-psf.npy.
object_distance (with mask=; metres or a string with a unit, '2m', 'inf'): refocus, as
`decode --object-distance`: the PSF of an object at that distance; where the pitch there is
not a whole number of pixels per cell, the exact-geometry PSF over the frame with
model='linear' and crop='none'; the result's refocus says which {object_distance_m, pitch_px,
whole_pixels_per_cell, mismatch_px, geometry}.
progress: called every poll_s seconds while the decode runs with {iteration (the iterations
each channel has finished), max_iterations (iters; 0 for the closed-form wiener and tikhonov),
seconds (elapsed)}; return False to stop: an iterative method ends after its current
iteration and returns the estimate so far with interrupted = True (as the CLI writes it).
Ctrl-C stops it the same way and raises KeyboardInterrupt.
Returns {image, method (the method that ran), channels: [{iterations, objective, residual,
converged, interrupted, seconds, history: (n, 4) array of iteration, seconds, objective,
residual}], interrupted, window: (row, col, rows, cols), period_check, chosen: the settings read
from the data, {name: {value, reason}} for each of background, model, crop, method, nonnegative
left to 'auto'}. A mono `image` owns the library's buffer; a
module-made mono capture and PSF summing to 1 are used without copies.)");
}

}  // namespace pinmask::python
