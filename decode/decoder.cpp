// decode_plane: validates the inputs once, builds the convolution model and dispatches to the
// algorithm of decode/. Solvers work on the model's working grid; the image returned is the
// capture window of the estimate.
#include "decode/decoder.hpp"

#include <chrono>
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "decode/convolution.hpp"
#include "decode/decode_method.hpp"
#include "decode/richardson_lucy.hpp"
#include "decode/tikhonov.hpp"
#include "decode/tv_l2.hpp"
#include "decode/tvqc.hpp"
#include "decode/wiener.hpp"

namespace pinmask {
namespace {

std::string num(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

std::string size_text(Eigen::Index r, Eigen::Index c) {
    return std::to_string(r) + " x " + std::to_string(c);
}

void check_nonnegative(const char* field, double v) {
    if (!(v >= 0.0) || !std::isfinite(v))
        throw invalid_field(field, num(v), "must be finite and >= 0");
}

void validate(const Plane& capture, const Plane& psf, const DecodeOptions& o) {
    if (capture.size() == 0) throw invalid_field("capture", "empty", "needs at least one pixel");
    if (!is_all_finite(capture)) {
        throw invalid_field("capture", "non-finite values", "every pixel must be finite");
    }
    if (psf.size() == 0) throw invalid_field("psf", "empty", "needs at least one pixel");
    if (!is_all_finite(psf))
        throw invalid_field("psf", "non-finite values", "every pixel must be finite");
    if (!(psf.sum() > 0.0)) throw invalid_field("psf sum", num(psf.sum()), "must be > 0");
    check_nonnegative("nsr", o.nsr);
    check_nonnegative("lambda", o.lambda);
    if (o.eps) check_nonnegative("eps", *o.eps);
    if (o.noise_sigma) check_nonnegative("noise_sigma", *o.noise_sigma);
    check_nonnegative("tolerance", o.tolerance);
    if (o.max_iterations < 0) {
        throw invalid_field("max_iterations", std::to_string(o.max_iterations), "must be >= 0");
    }
}

void check_work_plane(const char* field, const Plane& p, const ConvGeometry& g) {
    if (p.rows() != g.work_rows || p.cols() != g.work_cols) {
        throw invalid_field(field, size_text(p.rows(), p.cols()),
                            "must have the working size " + size_text(g.work_rows, g.work_cols));
    }
    if (!is_all_finite(p)) throw invalid_field(field, "non-finite values", "must be finite");
}

Plane apply_filter(const WienerFilter& f, const Plane& p, bool single, SpectralSums& sums) {
    Plane out;
    if (single) {
        WienerFilter::WorkspaceF ws;
        f.apply_single(p, out, ws, &sums);
    } else {
        WienerFilter::Workspace ws;
        f.apply(p, out, ws, &sums);
    }
    return out;
}

// The filter of a closed-form method from the operator's OTF (the PSF is transformed once), and
// in `weight` its penalty as a half-spectrum weight (SpectralSums): nsr ||x||^2, the
// per-frequency (1/N) sum_k NSR(k) |X(k)|^2, or lambda ||L x||^2.
WienerFilter closed_form_filter(const ConvolutionOperator& op, const DecodeOptions& o,
                                Plane& weight) {
    const ConvGeometry& g = op.geometry();
    const int R = g.work_rows, C = g.work_cols;
    if (o.method == DecodeMethod::kWiener) {
        if (o.nsr_per_frequency) {
            check_work_plane("nsr_per_frequency", *o.nsr_per_frequency, g);
            weight = fold_full_spectrum_weight(*o.nsr_per_frequency);
            return WienerFilter::from_otf(op.otf(), R, C, *o.nsr_per_frequency);
        }
        weight = o.nsr * half_spectrum_multiplicity(R, C);
        return WienerFilter::from_otf(op.otf(), R, C, o.nsr);
    }
    weight = o.lambda * tikhonov_symbol(R, C, o.regulariser) * half_spectrum_multiplicity(R, C);
    return make_tikhonov_filter_from_otf(op.otf(), R, C, o.lambda, o.regulariser);
}

// Closed-form methods: x = G p on the working grid (capture zero-padded for the linear model).
// Transforms: the PSF's OTF (one forward, shared by the filter and the model) and the filter's
// r2c + c2r pair. The penalty, and for the cyclic model the residual ||h (*) x - p||, are summed
// over the spectrum in the filter's own pass (Parseval); only the linear model's residual, which
// sees the crop, costs another pair (A x in the spatial domain).
DecodeResult decode_closed_form(const Plane& capture, const Plane& psf, const DecodeOptions& o,
                                const ConvGeometry& g) {
    const ConvolutionOperator op(psf, g);
    const bool cyclic = g.model == ConvModel::kCyclic;
    Plane weight;
    const WienerFilter filter = closed_form_filter(op, o, weight);
    SpectralSums sums;
    sums.weight = &weight;
    if (cyclic) sums.otf = &op.otf();
    const Plane x =
        apply_filter(filter, cyclic ? capture : pad_to_work(g, capture), o.single_precision, sums);
    const double res2 = cyclic ? sums.residual2 : (op.apply(x) - capture).square().sum();
    DecodeResult r;
    r.residual = std::sqrt(res2);
    r.objective = res2 + sums.penalty;
    r.image = crop_to_capture(g, x);
    return r;
}

void copy_iterative(const DecodeOptions& o, IterativeOptions& it) {
    it.max_iterations = o.max_iterations;
    it.tolerance = o.tolerance;
    it.record_history = o.record_history;
    it.stop = o.stop;
}

// Iterative methods on the working grid; the result's image is cropped to the capture.
DecodeResult decode_iterative(const Plane& capture, const Plane& psf, const DecodeOptions& o,
                              const ConvGeometry& g) {
    const ConvolutionOperator op(psf, g);
    const Plane* warm = o.warm_start ? &*o.warm_start : nullptr;
    DecodeResult r;
    switch (o.method) {
        case DecodeMethod::kTv: {
            TvL2Options t;
            copy_iterative(o, t);
            t.lambda = o.lambda;
            t.nonnegative = o.nonnegative;
            t.single_precision = o.single_precision;
            r = solve_tv_l2(op, capture, t, warm);
            break;
        }
        case DecodeMethod::kTvqc: {
            TvqcOptions t;
            copy_iterative(o, t);
            t.nonnegative = o.nonnegative;
            if (o.eps) {
                t.eps = *o.eps;
            } else if (o.noise_sigma) {
                t.eps = tvqc_eps_from_sigma(*o.noise_sigma, capture.size());
            } else {
                throw invalid_field("eps", "unset",
                                    "TVQC needs eps or noise_sigma (eps = sigma sqrt(N) "
                                    "sqrt(1 + 2 sqrt(2 / N)))");
            }
            r = solve_tvqc(op, capture, t, warm);
            break;
        }
        case DecodeMethod::kRichardsonLucy: {
            RichardsonLucyOptions t;
            copy_iterative(o, t);
            r = solve_richardson_lucy(op, psf, capture, t, warm);
            break;
        }
        default:
            throw invalid_field("method", std::to_string(static_cast<int>(o.method)),
                                "is not an iterative method");
    }
    r.image = crop_to_capture(g, r.image);
    return r;
}

}  // namespace

DecodeResult decode_plane(const Plane& capture, const Plane& psf, const DecodeOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    validate(capture, psf, options);
    const ConvGeometry g = make_conv_geometry(
        options.model, static_cast<int>(capture.rows()), static_cast<int>(capture.cols()),
        static_cast<int>(psf.rows()), static_cast<int>(psf.cols()));
    if (options.warm_start) check_work_plane("warm_start", *options.warm_start, g);

    // Solve for p / s: every method is equivariant under (p, x, lambda_tv, eps) -> s (...).
    const double peak = capture.abs().maxCoeff();
    const double s = peak > 0.0 ? peak : 1.0;
    const Plane p = capture / s;
    DecodeOptions o = options;
    o.lambda = options.method == DecodeMethod::kTv ? options.lambda / s : options.lambda;
    if (o.eps) *o.eps /= s;
    if (o.noise_sigma) *o.noise_sigma /= s;
    if (o.warm_start) *o.warm_start /= s;

    DecodeResult r;
    switch (o.method) {
        case DecodeMethod::kWiener:
        case DecodeMethod::kTikhonov:
            r = decode_closed_form(p, psf, o, g);
            break;
        case DecodeMethod::kTv:
        case DecodeMethod::kTvqc:
        case DecodeMethod::kRichardsonLucy:
            r = decode_iterative(p, psf, o, g);
            break;
        default:
            throw invalid_field("method", std::to_string(static_cast<int>(o.method)),
                                "is not a decode method (" + decode_method_names() + ")");
    }
    // Back to the capture's units: objectives quadratic in p scale by s^2, TV and the
    // I-divergence by s; TVQC's recorded residual is relative to eps (unchanged).
    const bool linear_objective =
        o.method == DecodeMethod::kTvqc || o.method == DecodeMethod::kRichardsonLucy;
    const double obj_scale = linear_objective ? s : s * s;
    r.image *= s;
    r.residual *= s;
    r.objective *= obj_scale;
    for (IterationRecord& h : r.history) {
        h.objective *= obj_scale;
        if (o.method != DecodeMethod::kTvqc) h.residual *= s;
    }
    // The objective is quadratic in p for most methods: beyond |p| ~ 1e154 it leaves the double
    // range and is reported as +inf (a figure, not the result); image and residual must be finite.
    if (!is_all_finite(r.image) || !std::isfinite(r.residual) || std::isnan(r.objective)) {
        throw RuntimeFailure(std::string("decode (") + decode_method_name(o.method) +
                             "): the estimate is not finite (largest capture value " + num(peak) +
                             "); nothing is written");
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace pinmask
