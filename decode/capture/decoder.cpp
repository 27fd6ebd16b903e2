// decode_plane: validates the inputs once, builds the convolution model and dispatches to the
// algorithm of decode/. Solvers work on the model's working grid; the image returned is the
// capture window of the estimate.
#include "decode/capture/decoder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/number_format.hpp"
#include "decode/capture/capture_defaults.hpp"
#include "decode/solvers/auto_weight.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/plan_cache.hpp"
#include "decode/solvers/richardson_lucy.hpp"
#include "decode/solvers/tikhonov.hpp"
#include "decode/solvers/tv_l2.hpp"
#include "decode/solvers/tvqc.hpp"
#include "decode/solvers/wiener.hpp"

namespace pinmask {
namespace {

std::string size_text(Eigen::Index r, Eigen::Index c) {
    return std::to_string(r) + " x " + std::to_string(c);
}

// `field` is a field reference (core/errors/field_names): each face spells it as its flag or
// keyword.
void check_nonnegative(const std::string& field, double v) {
    if (!(v >= 0.0) || !std::isfinite(v))
        throw invalid_field(field, format_number(v, 17), "must be finite and >= 0");
}

// Validates capture and PSF and returns max |capture|, one pass over each (a warm 256 x 256
// Wiener decode spent 8 % in separate finiteness, sum and peak passes): the peak propagates a
// NaN and is infinite for an infinite pixel; a finite PSF sum proves every PSF value finite (an
// overflowing sum of finite values is told apart by the full test).
double validate_inputs(const Plane& capture, const Plane& psf) {
    if (capture.size() == 0) throw invalid_field("capture", "empty", "needs at least one pixel");
    const double peak = capture.abs().maxCoeff<Eigen::PropagateNaN>();
    if (!std::isfinite(peak)) {
        throw invalid_field("capture", "non-finite values", "every pixel must be finite");
    }
    if (psf.size() == 0) throw invalid_field("psf", "empty", "needs at least one pixel");
    const double sum = psf.sum();
    if (!std::isfinite(sum) && !is_all_finite(psf))
        throw invalid_field("psf", "non-finite values", "every pixel must be finite");
    if (!(sum > 0.0)) throw invalid_field("psf sum", format_number(sum, 17), "must be > 0");
    return peak;
}

void check_work_plane(const std::string& field, const Plane& p, const ConvGeometry& g) {
    if (p.rows() != g.work_rows || p.cols() != g.work_cols) {
        throw invalid_field(field, size_text(p.rows(), p.cols()),
                            "must have the working size " + size_text(g.work_rows, g.work_cols));
    }
    if (!is_all_finite(p)) throw invalid_field(field, "non-finite values", "must be finite");
}

Plane apply_filter(const WienerFilter& f, const Plane& p, bool single, SpectralSums& sums,
                   double scale) {
    Plane out;
    if (single) {
        WienerFilter::WorkspaceF ws;
        f.apply_single(p, out, ws, &sums, scale);
    } else {
        WienerFilter::Workspace ws;
        f.apply(p, out, ws, &sums, scale);
    }
    return out;
}

// The power of two in (peak, 2 peak] (1 for a zero capture): dividing by it is exact, so a
// closed-form decode of capture / scale times scale is the decode of the capture itself, in a
// range where neither float32 nor the squared sums overflow.
double power_of_two_above(double peak) {
    if (!(peak > 0.0)) return 1.0;
    int e = 0;
    std::frexp(peak, &e);
    return std::ldexp(1.0, e);
}

// The operator A: from DecodeOptions::plans when set (built once per PSF and grid), else new.
std::shared_ptr<const ConvolutionOperator> operator_for(const Plane& psf, const ConvGeometry& g,
                                                        const DecodeOptions& o) {
    if (o.plans) return o.plans->conv_operator(psf, g);
    return std::make_shared<const ConvolutionOperator>(psf, g);
}

// The penalty of a closed-form method in `sums`: nsr ||x||^2 as a uniform weight (no plane),
// else a half-spectrum weight plane kept in `storage`: the per-frequency (1/N) sum_k NSR(k)
// |X(k)|^2, or lambda ||L x||^2.
void set_closed_form_penalty(const ConvGeometry& g, const DecodeOptions& o, SpectralSums& sums,
                             Plane& storage) {
    const int R = g.work_rows, C = g.work_cols;
    if (o.method == DecodeMethod::kWiener) {
        const WienerParams& w = o.wiener;
        if (!w.nsr_per_frequency) {
            sums.uniform_weight = w.nsr;
            return;
        }
        storage = fold_full_spectrum_weight(*w.nsr_per_frequency);
    } else {
        const TikhonovParams& t = o.tikhonov;
        storage =
            t.lambda * tikhonov_symbol(R, C, t.regulariser) * half_spectrum_multiplicity(R, C);
    }
    sums.weight = &storage;
}

// Closed-form methods: x = G p on the working grid (capture zero-padded for the linear model).
// Transforms: the PSF's OTF (one forward, shared by the filter and the model) and the filter's
// r2c + c2r pair; with DecodeOptions::plans the OTF and a scalar-NSR or Tikhonov filter come
// from the cache (same bytes). The penalty, and for the cyclic model the residual
// ||h (*) x - p||, are summed over the spectrum in the filter's own pass (Parseval); only the
// linear model's residual, which sees the crop, costs another pair (A x in the spatial domain).
// The capture is decoded as it is: the filter is linear, so its range is handled by an exact
// power-of-two scale inside the filter's own conversions (float32 always; double only outside
// 2^-100..2^100, where the squared sums could leave the range), not by a scaled copy.
DecodeResult decode_closed_form(const Plane& capture, const Plane& psf, const DecodeOptions& given,
                                const ConvGeometry& g, double peak) {
    const auto op_ptr = operator_for(psf, g, given);
    const ConvolutionOperator& op = *op_ptr;
    // An automatic weight is chosen here and the decode runs as with that weight given.
    DecodeOptions o = given;
    std::optional<AutoWeight> chosen;
    if (given.method == DecodeMethod::kWiener ? given.wiener.automatic : given.tikhonov.automatic) {
        const bool wiener = given.method == DecodeMethod::kWiener;
        const Plane symbol =
            tikhonov_symbol(g.work_rows, g.work_cols,
                            wiener ? TikhonovRegulariser::kIdentity : given.tikhonov.regulariser);
        chosen = choose_closed_form_weight(capture, op.otf(), symbol, g.work_rows, g.work_cols,
                                           given.auto_noise_sigma);
        if (wiener) {
            o.wiener.nsr = chosen->weight;
            o.wiener.automatic = false;
        } else {
            o.tikhonov.lambda = chosen->weight;
            o.tikhonov.automatic = false;
        }
    }
    const bool cyclic = g.model == ConvModel::kCyclic;
    const bool cacheable =
        !(o.method == DecodeMethod::kWiener && o.wiener.nsr_per_frequency.has_value());
    const std::shared_ptr<const WienerFilter> filter =
        o.plans && cacheable ? o.plans->filter(psf, g, o)
                             : std::make_shared<const WienerFilter>(closed_form_filter(op, o));
    SpectralSums sums;
    Plane weight;
    set_closed_form_penalty(g, o, sums, weight);
    if (cyclic) sums.otf = &op.otf();
    const double pow2 = power_of_two_above(peak);
    const double scale = o.single_precision || pow2 > 0x1p100 || pow2 < 0x1p-100 ? pow2 : 1.0;
    Plane x = apply_filter(*filter, cyclic ? capture : pad_to_work(g, capture), o.single_precision,
                           sums, scale);
    // The sums are those of capture / scale; the linear model's residual is taken the same way.
    const double res2 =
        cyclic ? sums.residual2 : ((op.apply(x) - capture) * (1.0 / scale)).square().sum();
    DecodeResult r;
    r.residual = std::sqrt(res2) * scale;
    r.objective = (res2 + sums.penalty) * scale * scale;
    // The cyclic model's working grid is the capture: nothing to crop.
    r.image = cyclic ? std::move(x) : crop_to_capture(g, x);
    r.auto_weight = chosen;
    return r;
}

void copy_iterative(const IterativeParams& o, IterativeOptions& it) {
    it.max_iterations = o.max_iterations;
    it.tolerance = o.tolerance;
    it.record_history = o.record_history;
    it.stop = o.stop;
    it.iterations_done = o.iterations_done;
}

// Iterative methods on the working grid; the result's image is cropped to the capture.
DecodeResult decode_iterative(const Plane& capture, const Plane& psf, const DecodeOptions& o,
                              const ConvGeometry& g) {
    const auto op_ptr = operator_for(psf, g, o);
    const ConvolutionOperator& op = *op_ptr;
    const Plane* warm = o.iterative.warm_start ? &*o.iterative.warm_start : nullptr;
    DecodeResult r;
    switch (o.method) {
        case DecodeMethod::kTv: {
            TvL2Options t;
            copy_iterative(o.iterative, t);
            t.lambda = o.tv.lambda;
            t.nonnegative = o.tv.nonnegative;
            t.single_precision = o.single_precision;
            r = solve_tv_l2(op, capture, t, warm);
            break;
        }
        case DecodeMethod::kTvqc: {
            TvqcOptions t;
            copy_iterative(o.iterative, t);
            t.nonnegative = o.tvqc.nonnegative;
            t.single_precision = o.single_precision;
            // TvqcParams::validate guarantees exactly one of eps and noise_sigma.
            t.eps =
                o.tvqc.eps ? *o.tvqc.eps : tvqc_eps_from_sigma(*o.tvqc.noise_sigma, capture.size());
            r = solve_tvqc(op, capture, t, warm);
            break;
        }
        case DecodeMethod::kRichardsonLucy: {
            RichardsonLucyOptions t;
            copy_iterative(o.iterative, t);
            t.single_precision = o.single_precision;
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

// The warning for a given TV weight more than 10 times from the automatic one, else "".
std::string tv_weight_warning(double lambda, const AutoWeight& a) {
    if (!(a.weight > 0.0)) return "";
    const double ratio = lambda / a.weight;
    if (ratio <= 10.0 && ratio >= 0.1) return "";
    return field_ref("lambda") + " " + format_number(lambda, 4) + " is " + format_number(ratio, 2) +
           " times the automatic weight " + format_number(a.weight, 4) +
           " for this capture's noise (sigma " + format_number(a.noise_sigma, 4) + "): " +
           (ratio > 1 ? "the estimate is over-smoothed" : "the noise is barely regularised") +
           "; " + field_ref("lambda") + " auto chooses it";
}

// The warning for a closed form on the linear model with a capture that fills the frame
// (decode/capture/capture_defaults.hpp border_fill).
std::string frame_filling_warning(const Plane& capture, DecodeMethod method) {
    const double fill = border_fill(capture);
    if (fill < kFrameFillingBorderFill) return "";
    return std::string(decode_method_name(method)) + " on the linear model reads the light " +
           "beyond the sensor as zero, and this capture fills the frame (its border averages " +
           format_number(100 * fill, 3) + " % of its mean): expect ringing from the edges; " +
           field_ref("method") + " tv solves the linear model exactly";
}

}  // namespace

WienerFilter closed_form_filter(const ConvolutionOperator& op, const DecodeOptions& o) {
    const ConvGeometry& g = op.geometry();
    const int R = g.work_rows, C = g.work_cols;
    if (o.method == DecodeMethod::kWiener) {
        const WienerParams& w = o.wiener;
        if (w.nsr_per_frequency) {
            check_work_plane(field_ref("nsr_map"), *w.nsr_per_frequency, g);
            return WienerFilter::from_otf(op.otf(), R, C, *w.nsr_per_frequency);
        }
        return WienerFilter::from_otf(op.otf(), R, C, w.nsr);
    }
    if (o.method != DecodeMethod::kTikhonov)
        throw InvalidInput("closed_form_filter: the method must be wiener or tikhonov");
    const TikhonovParams& t = o.tikhonov;
    return make_tikhonov_filter_from_otf(op.otf(), R, C, t.lambda, t.regulariser);
}

void IterativeParams::validate() const {
    if (max_iterations < 0) {
        throw invalid_field(field_ref("iterations"), std::to_string(max_iterations),
                            "must be >= 0");
    }
    check_nonnegative(field_ref("tolerance"), tolerance);
    if (warm_start && !is_all_finite(*warm_start))
        throw invalid_field("iterative.warm_start", "non-finite values", "must be finite");
}

void WienerParams::validate() const {
    check_nonnegative(field_ref("wiener_nsr"), nsr);
    if (nsr_per_frequency &&
        !(nsr_per_frequency->minCoeff() >= 0.0 && is_all_finite(*nsr_per_frequency))) {
        throw invalid_field(field_ref("nsr_map"), "negative or non-finite values",
                            "every value must be finite and >= 0");
    }
    if (automatic && nsr_per_frequency)
        throw invalid_field(field_ref("nsr_map"), "given", "excludes the automatic NSR");
}

void TikhonovParams::validate() const {
    check_nonnegative(field_ref("lambda"), lambda);
    if (regulariser != TikhonovRegulariser::kIdentity &&
        regulariser != TikhonovRegulariser::kGradient) {
        throw invalid_field(field_ref("regulariser"), std::to_string(static_cast<int>(regulariser)),
                            "must be identity or gradient");
    }
}

void TvParams::validate() const {
    if (!automatic) check_nonnegative(field_ref("lambda"), lambda);
}

void TvqcParams::validate() const {
    if (eps) check_nonnegative(field_ref("eps"), *eps);
    if (noise_sigma) check_nonnegative(field_ref("noise_sigma"), *noise_sigma);
    if (!eps && !noise_sigma) {
        throw invalid_field(field_ref("eps"), "unset",
                            "TVQC needs eps or noise_sigma (eps = sigma sqrt(N) "
                            "sqrt(1 + 2 sqrt(2 / N)))");
    }
    if (eps && noise_sigma) {
        throw invalid_field(field_ref("noise_sigma"), format_number(*noise_sigma, 17),
                            "must not be set together with tvqc.eps (" + format_number(*eps, 17) +
                                "): give one of them");
    }
}

void DecodeOptions::validate() const {
    if (model != ConvModel::kCyclic && model != ConvModel::kLinear)
        throw invalid_field("model", std::to_string(static_cast<int>(model)),
                            "must be cyclic or linear");
    switch (method) {
        case DecodeMethod::kWiener:
            wiener.validate();
            break;
        case DecodeMethod::kTikhonov:
            tikhonov.validate();
            break;
        case DecodeMethod::kTv:
            tv.validate();
            break;
        case DecodeMethod::kTvqc:
            tvqc.validate();
            break;
        case DecodeMethod::kRichardsonLucy:
            break;
        default:
            throw invalid_field("method", std::to_string(static_cast<int>(method)),
                                "is not a decode method (" + decode_method_names() + ")");
    }
    if (auto_noise_sigma) check_nonnegative("auto_noise_sigma", *auto_noise_sigma);
    // Checked for every method (its size needs the working grid: decode_plane checks that).
    iterative.validate();
}

DecodeResult decode_plane(const Plane& capture, const Plane& psf, const DecodeOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    const double peak = validate_inputs(capture, psf);
    options.validate();
    const ConvGeometry g = make_conv_geometry(
        options.model, static_cast<int>(capture.rows()), static_cast<int>(capture.cols()),
        static_cast<int>(psf.rows()), static_cast<int>(psf.cols()));
    if (options.iterative.warm_start)
        check_work_plane("iterative.warm_start", *options.iterative.warm_start, g);

    DecodeResult r;
    double s = 1.0;  // the iterative methods' capture scale (closed forms scale inside)
    switch (options.method) {
        case DecodeMethod::kWiener:
        case DecodeMethod::kTikhonov:
            r = decode_closed_form(capture, psf, options, g, peak);
            if (g.model == ConvModel::kLinear) {
                const std::string w = frame_filling_warning(capture, options.method);
                if (!w.empty()) r.warnings.push_back(w);
            }
            break;
        case DecodeMethod::kTv:
        case DecodeMethod::kTvqc:
        case DecodeMethod::kRichardsonLucy: {
            // Solve for p / s: every method is equivariant under (p, x, lambda_tv, eps) -> s (...).
            s = peak > 0.0 ? peak : 1.0;
            const Plane p = capture / s;
            DecodeOptions o = options;
            std::optional<AutoWeight> tv_auto;
            std::string tv_warning;
            if (o.method == DecodeMethod::kTv) {
                const AutoWeight a = choose_tv_weight(capture, psf, o.auto_noise_sigma);
                if (o.tv.automatic) {
                    tv_auto = a;
                    o.tv.lambda = a.weight;
                } else {
                    tv_warning = tv_weight_warning(o.tv.lambda, a);
                }
            }
            o.tv.lambda /= s;
            if (o.tvqc.eps) *o.tvqc.eps /= s;
            if (o.tvqc.noise_sigma) *o.tvqc.noise_sigma /= s;
            if (o.iterative.warm_start) *o.iterative.warm_start /= s;
            r = decode_iterative(p, psf, o, g);
            r.auto_weight = tv_auto;
            if (!tv_warning.empty()) r.warnings.push_back(tv_warning);
            break;
        }
        default:
            throw invalid_field("method", std::to_string(static_cast<int>(options.method)),
                                "is not a decode method (" + decode_method_names() + ")");
    }
    if (s != 1.0) {
        // Back to the capture's units: objectives quadratic in p scale by s^2, TV and the
        // I-divergence by s; TVQC's recorded residual is relative to eps (unchanged).
        const bool linear_objective = options.method == DecodeMethod::kTvqc ||
                                      options.method == DecodeMethod::kRichardsonLucy;
        const double obj_scale = linear_objective ? s : s * s;
        r.image *= s;
        r.residual *= s;
        r.objective *= obj_scale;
        for (IterationRecord& h : r.history) {
            h.objective *= obj_scale;
            if (options.method != DecodeMethod::kTvqc) h.residual *= s;
        }
    }
    // The objective is quadratic in p for most methods: beyond |p| ~ 1e154 it leaves the double
    // range and is reported as +inf (a figure, not the result); image and residual must be finite.
    if (!is_all_finite(r.image) || !std::isfinite(r.residual) || std::isnan(r.objective)) {
        throw RuntimeFailure(std::string("decode (") + decode_method_name(options.method) +
                             "): the estimate is not finite (largest capture value " +
                             format_number(peak, 17) + "); nothing is written");
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace pinmask
