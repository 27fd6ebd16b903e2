// Decoding: decode() is `pinmask decode` on arrays, one call of decode/capture_pipeline
// (decode_capture) with the options the CLI maps from the same flags (decode_options,
// capture_decode_options, parse_crop): names, defaults, messages and numbers are the
// CLI's.
#include <atomic>

#include "core/error.hpp"
#include "decode/capture.hpp"
#include "decode/capture_pipeline.hpp"
#include "decode/decode_request.hpp"
#include "decode/decoder.hpp"
#include "decode/period.hpp"
#include "design/psf.hpp"
#include "python/common.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

struct DecodeOutput {
    std::vector<DecodeResult> results;
    CropWindow window;
    PeriodCheck period;
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

// `pinmask decode`'s library pipeline (decode/capture_pipeline decode_capture: dark frame,
// period check, crop, PSF to unit sum, precision, each channel decoded) with the CLI's own
// options (capture_decode_options). The pipeline owns its inputs: a borrowed capture or PSF
// is copied into it (a C++ copy, not a numpy conversion: input_copies() does not count it).
DecodeOutput decode_pipeline(CaptureArg& cap, const PlaneArg& psf_in,
                             const std::optional<Image>& dark, const DecodeRequest& r,
                             const std::atomic<bool>* stop) {
    CaptureDecodeOptions options = capture_decode_options(r);
    options.decode.stop = stop;
    options.validate();
    CaptureDecodeInputs in;
    in.capture = cap.plane ? Image(*cap.plane) : std::move(cap.image);
    in.psf = Image(psf_in.get());
    in.dark = dark;
    CaptureDecodeResult res = decode_capture(std::move(in), options);
    DecodeOutput out;
    out.window = res.summary.window;
    out.period = res.summary.period;
    out.results = std::move(res.summary.channels);
    for (std::size_t i = 0; i < out.results.size() && i < res.estimate.channels.size(); ++i)
        out.results[i].image = std::move(res.estimate.channels[i]);
    return out;
}

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

}  // namespace

void bind_decode(py::module_& m) {
    m.def(
        "decode",
        [](const py::handle& capture, const py::handle& psf, const py::handle& mask,
           const std::string& method, const std::string& model, double nsr, double lambda_,
           const std::string& regulariser, std::optional<double> eps,
           std::optional<double> noise_sigma, bool nonneg, int iters, double tol,
           const py::handle& crop, const py::handle& dark, const py::object& progress,
           double poll_s) {
            DecodeRequest r;
            r.method = method;
            r.model = model;
            r.nsr = nsr;
            r.lambda = lambda_;
            r.regulariser = regulariser;
            r.eps = eps;
            r.noise_sigma = noise_sigma;
            r.nonnegative = nonneg;
            r.iterations = iters;
            r.tolerance = tol;
            if (model != "cyclic" && model != "linear")
                throw invalid_field("--model", model, "must be cyclic or linear");
            if (regulariser != "identity" && regulariser != "gradient")
                throw invalid_field("--regulariser", regulariser, "must be identity or gradient");
            if (iters < 0) throw invalid_field("--iters", std::to_string(iters), "must be >= 0");
            if (eps && noise_sigma)
                throw InvalidInput("--eps excludes --noise-sigma (eps= or noise_sigma=, not both)");
            if (py::isinstance<py::str>(crop)) {
                r.crop = crop.cast<std::string>();
            } else {  // (row, col) of the top-left pixel: the CLI's X,Y is col,row
                const auto rc = crop.cast<std::pair<int, int>>();
                r.crop = std::to_string(rc.second) + "," + std::to_string(rc.first);
            }
            if (psf.is_none() == mask.is_none())
                throw InvalidInput(
                    "decode needs the PSF: give --mask FILE.mask.json or --psf FILE (psf= an "
                    "array or mask= a Mask or path, not both)");
            std::optional<PlaneArg> psf_arg;
            if (!psf.is_none()) {
                psf_arg = plane_arg(psf, "psf");
            } else {
                const Mask mk = mask_arg(mask);
                Plane p;
                {
                    py::gil_scoped_release release;
                    p = mask_psf(mk);
                }
                psf_arg = plane_arg(to_array(std::move(p)), "psf");
            }
            CaptureArg cap;
            std::optional<PlaneArg> borrowed_capture;
            if (is_library_buffer(capture)) {
                borrowed_capture = plane_arg(capture, "capture");
                cap.plane = &borrowed_capture->get();
            } else {
                cap.image = image_arg(capture, "capture");
            }
            std::optional<Image> dark_img;
            if (!dark.is_none()) dark_img = image_arg(dark, "dark");

            std::atomic<bool> stop{false};
            DecodeOutput out;
            const Poll poll = run_with_interrupt(
                [&] { out = decode_pipeline(cap, *psf_arg, dark_img, r, &stop); }, stop, progress,
                poll_s);

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
                c["residual"] = res.residual;
                c["converged"] = res.converged;
                c["interrupted"] = res.interrupted;
                c["seconds"] = res.seconds;
                c["history"] = hist;
                channels.append(c);
                any_interrupted = any_interrupted || res.interrupted;
                estimate.channels.push_back(std::move(res.image));
            }
            // Ctrl-C that cut nothing short (closed form, or already finished) is not swallowed.
            if (poll == Poll::kKeyboardInterrupt && !any_interrupted) raise_keyboard_interrupt();
            check_image_finite(estimate, "decoded estimate");
            d["image"] = image_to_array(std::move(estimate));
            d["channels"] = channels;
            d["interrupted"] = any_interrupted;
            d["window"] =
                py::make_tuple(out.window.row, out.window.col, out.window.rows, out.window.cols);
            d["period_check"] = period_dict(out.period);
            return d;
        },
        py::arg("capture"), py::arg("psf") = py::none(), py::arg("mask") = py::none(),
        py::arg("method") = "wiener", py::arg("model") = "cyclic", py::arg("nsr") = 0.01,
        py::arg("lambda_") = 1e-3, py::arg("regulariser") = "identity", py::arg("eps") = py::none(),
        py::arg("noise_sigma") = py::none(), py::arg("nonneg") = false, py::arg("iters") = 200,
        py::arg("tol") = 1e-4, py::arg("crop") = "center", py::arg("dark") = py::none(),
        py::arg("progress") = py::none(), py::arg("poll_s") = 0.05,
        R"(Decodes a capture as `pinmask decode` does with its default preprocessing
(--background none, --downsample 0, --normalize none): dark frame subtracted, period check,
crop of one period, PSF scaled to unit sum, each channel decoded (colour channels in parallel).

capture: (rows, cols) or (rows, cols, channels) array, capture units. psf: a PSF array (any
sum > 0), or mask: a Mask or *.mask.json path (its PSF is synthesised).
method: wiener (deconvwnr: PSF centre floor(size/2) at the origin, scalar nsr, real part) |
tikhonov (lambda_, regulariser identity|gradient) | tv (TV-L2 ADMM, lambda_) | tvqc (min TV
s.t. ||Ax - p||_2 <= eps, or eps from noise_sigma) | richardson-lucy. model: cyclic
(circular convolution over one period) | linear (zero-padded, then cropped). nonneg: x >= 0 for
tv/tvqc. iters, tol: iterative methods (relative change of x). crop: 'center' | 'none' |
(row, col) of the period's top-left pixel. dark: dark frame, same size (1 or the capture's
channels).
progress: called every poll_s seconds with the elapsed seconds while the decode runs; return
False to stop. Ctrl-C (KeyboardInterrupt) or False ends an iterative method after its current
iteration and returns the estimate so far with interrupted = True (as the CLI writes it); a
Ctrl-C that cut nothing short (a closed-form method, or one that had finished) is raised.
Returns {image, channels: [{iterations, objective, residual, converged, interrupted, seconds,
history: (n, 4) array of iteration, seconds, objective, residual}], interrupted,
window: (row, col, rows, cols), period_check}. A mono `image` owns the library's buffer; a
module-made mono capture and PSF summing to 1 are used without copies.)");
}

}  // namespace pinmask::python
