#include "decode/tv_l2.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "decode/gradient.hpp"

namespace pinmask {
namespace {

// Residual balancing (Boyd et al. 2011, sec. 3.4.1): adapt when one residual is kMu times the
// other, by the factor kTau, every kAdaptEvery iterations during the first half of the run.
constexpr double kMu = 10.0;
constexpr double kTau = 2.0;
constexpr int kAdaptEvery = 10;

// Multiplies rho by kTau, divides it, or leaves it; returns the factor applied.
double balance(double primal, double dual, double& rho) {
    if (primal > kMu * dual) {
        rho *= kTau;
        return kTau;
    }
    if (dual > kMu * primal) {
        rho /= kTau;
        return 1.0 / kTau;
    }
    return 1.0;
}

void check_capture(const Plane& capture, const ConvGeometry& g) {
    if (capture.rows() != g.capture_rows || capture.cols() != g.capture_cols) {
        throw invalid_field(
            "capture", std::to_string(capture.rows()) + " x " + std::to_string(capture.cols()),
            "must match the operator's capture size " + std::to_string(g.capture_rows) + " x " +
                std::to_string(g.capture_cols));
    }
}

}  // namespace

double tv_l2_objective(const ConvolutionOperator& op, const Plane& capture, const Plane& x,
                       double lambda) {
    return 0.5 * (op.apply(x) - capture).square().sum() + lambda * total_variation(x);
}

DecodeResult solve_tv_l2(const ConvolutionOperator& op, const Plane& capture, const TvL2Options& o,
                         const Plane* warm_start) {
    const SolverClock clock;
    const ConvGeometry& g = op.geometry();
    validate_iterative_options(o);
    check_capture(capture, g);
    if (!(o.lambda >= 0.0) || !std::isfinite(o.lambda)) {
        throw invalid_field("lambda", std::to_string(o.lambda), "must be finite and >= 0");
    }
    if (!(o.rho >= 0.0) || !std::isfinite(o.rho)) {
        throw invalid_field("rho", std::to_string(o.rho),
                            "must be finite and >= 0 (0 = automatic)");
    }
    if (warm_start) check_warm_start(*warm_start, g);

    const bool linear = g.model == ConvModel::kLinear;
    const bool nn = o.nonnegative;
    const Fft2& fft = op.fft();
    const ComplexPlane& H = op.otf();
    const ComplexPlane Hc = H.conjugate();
    const Plane h2 = H.abs2();
    const Plane gram = gradient_gram_symbol(g.work_rows, g.work_cols);
    const Plane p_pad = pad_to_work(g, capture);
    const ComplexPlane htp = linear ? ComplexPlane() : ComplexPlane(Hc * fft.forward(p_pad));
    Plane window;  // C^T C 1: 1 inside the capture window
    if (linear) window = pad_to_work(g, Plane::Ones(g.capture_rows, g.capture_cols));

    double rho = o.rho > 0.0 ? o.rho : std::max(h2.mean(), 1e-12);
    double rho_s = 1.0;
    Plane inv_denom;  // 1 / (x-step denominator); > 0 since H(0) = sum(psf) > 0 and rho > 0
    auto update_denominator = [&] {
        inv_denom = 1.0 / ((linear ? rho_s * h2 : h2) + rho * gram + (nn ? rho : 0.0));
    };
    update_denominator();

    Plane x = warm_start ? *warm_start : Plane::Zero(g.work_rows, g.work_cols);
    Plane gr, gc;
    gradient(x, gr, gc);
    Plane zr = gr, zc = gc, ur = Plane::Zero(gr.rows(), gr.cols()), uc = ur;
    Plane w, v;
    if (nn) {
        w = x.max(0.0);
        v = Plane::Zero(x.rows(), x.cols());
    }
    Plane s, eta, hx;
    if (linear) {
        hx = op.convolve(x);
        s = (p_pad + rho_s * hx) / (window + rho_s);  // an s-step, so the data enters at once
        eta = Plane::Zero(x.rows(), x.cols());
    }

    // Buffers reused by every iteration (no allocation inside the loop).
    ComplexPlane spec, spec2, scratch;
    Plane x_old(x.rows(), x.cols()), tmp(x_old), ar(x_old), ac(x_old), factor(x_old), ax;
    DecodeResult r;
    r.converged = false;
    const int adapt_until = o.max_iterations / 2;
    auto estimate = [&]() -> const Plane& { return nn ? w : x; };

    for (int k = 1; k <= o.max_iterations; ++k) {
        // x-step.
        ar = zr - ur;
        ac = zc - uc;
        divergence(ar, ac, tmp);
        if (nn) {
            tmp = rho * (w - v) - rho * tmp;
        } else {
            tmp *= -rho;
        }
        fft.forward(tmp, spec);
        if (linear) {
            tmp = s - eta;
            fft.forward(tmp, spec2);
            spec += rho_s * Hc * spec2;
        } else {
            spec += htp;
        }
        spec *= inv_denom.cast<std::complex<double>>();
        x_old.swap(x);
        fft.inverse(spec, x, scratch);
        const bool need_hx = linear || (o.record_history && !nn);
        if (need_hx) {  // H x from the same spectrum
            spec *= H;
            fft.inverse(spec, linear ? hx : ax, scratch);
        }

        // s-step (linear model).
        double prim_s = 0.0, dual_s = 0.0;
        if (linear) {
            tmp = s;
            s = (p_pad + rho_s * (hx + eta)) / (window + rho_s);
            eta += hx - s;
            prim_s = std::sqrt((hx - s).square().sum());
            dual_s = rho_s * std::sqrt((s - tmp).square().sum());
        }

        // z-step: isotropic shrinkage of grad x + u by lambda / rho.
        gradient(x, gr, gc);
        ar = gr + ur;
        ac = gc + uc;
        const double thr = o.lambda / rho;
        factor = (1.0 - thr / (ar.square() + ac.square()).sqrt().max(1e-300)).max(0.0);
        double dual_z =
            std::sqrt((zr - factor * ar).square().sum() + (zc - factor * ac).square().sum());
        zr = factor * ar;
        zc = factor * ac;
        ur = ar - zr;
        uc = ac - zc;
        double prim2 = (gr - zr).square().sum() + (gc - zc).square().sum();

        // w-step: projection on x >= 0.
        if (nn) {
            tmp = (x + v).max(0.0);
            dual_z = std::hypot(dual_z, std::sqrt((tmp - w).square().sum()));
            w.swap(tmp);
            v += x - w;
            prim2 += (x - w).square().sum();
        }

        r.iterations = k;
        const double change = relative_change(x, x_old);
        if (o.record_history) {
            IterationRecord rec;
            rec.iteration = k;
            if (nn) ax = op.convolve(w);  // H w on the working grid
            const Plane& a_est = nn ? ax : (linear ? hx : ax);
            const double res2 =
                (a_est.block(g.crop_row, g.crop_col, g.capture_rows, g.capture_cols) - capture)
                    .square()
                    .sum();
            rec.residual = std::sqrt(res2);
            rec.objective =
                0.5 * res2 + o.lambda * (nn ? total_variation(w) : total_variation(gr, gc));
            rec.seconds = clock.seconds();
            r.history.push_back(rec);
        }
        if (iteration_ends(change <= o.tolerance, o, r)) break;

        // Residual balancing of the penalties (rescaling the scaled duals).
        if (k % kAdaptEvery == 0 && k <= adapt_until) {
            const double f = balance(std::sqrt(prim2), rho * dual_z, rho);
            double fs = 1.0;
            if (linear) fs = balance(prim_s, dual_s, rho_s);
            if (f != 1.0) {
                ur /= f;
                uc /= f;
                if (nn) v /= f;
            }
            if (fs != 1.0) eta /= fs;
            if (f != 1.0 || fs != 1.0) update_denominator();
        }
    }
    if (o.max_iterations == 0) {
        r.converged = true;
        if (nn) w = x.max(0.0);
    }
    r.image = estimate();
    r.objective = tv_l2_objective(op, capture, r.image, o.lambda);
    r.residual = std::sqrt((op.apply(r.image) - capture).square().sum());
    r.seconds = clock.seconds();
    return r;
}

}  // namespace pinmask
