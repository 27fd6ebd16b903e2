#include "decode/solvers/richardson_lucy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "core/errors/error.hpp"
#include "decode/solvers/precision.hpp"

namespace pinmask {

double i_divergence(const Plane& p, const Plane& q) {
    const double floor = kRlTiny * std::max(p.maxCoeff(), 1e-300);
    double s = 0.0;
    for (Eigen::Index i = 0; i < p.size(); ++i) {
        const double pi = p.data()[i], qi = std::max(q.data()[i], floor);
        s += (pi > 0.0 ? pi * std::log(pi / qi) : 0.0) - pi + qi;
    }
    return s;
}

namespace {

// The iteration in precision T on x (working grid, updated in place; ax gets A x): per
// iteration one pass that forms the ratio p / A x from the inverse transform's output (into the
// zero-padded buffer for the linear model), the transform pair of A^T, one pass that updates x
// and sums its change, and the transform pair of A. The operator is used as H / H(0) (H(0) =
// sum a > 0, the largest |H| of a non-negative PSF) and the iterate as H(0) x: the RL update is
// invariant under that scaling, and it keeps every float32 quantity near 1 whatever the PSF's
// scale. Sums are in double; every buffer is allocated before the first iteration.
template <class T>
void iterate(const ConvolutionOperator& op, const Plane& p_d, const Plane& capture,
             const Plane& inv_at1_d, const RichardsonLucyOptions& o, Plane& x_io, Plane& ax_out,
             DecodeResult& r, const SolverClock& clock) {
    using Types = PrecisionTypes<T>;
    using P = typename Types::Plane;
    using S = typename Types::Spectrum;
    using Cx = std::complex<T>;
    const ConvGeometry& g = op.geometry();
    const int R = g.work_rows, W = g.work_cols, hc = W / 2 + 1;
    const int cr = g.crop_row, cc = g.crop_col, pr = g.capture_rows, pc = g.capture_cols;
    const bool linear = g.model == ConvModel::kLinear;
    const typename Types::Fft fft(R, W);
    const ComplexPlane& H = op.otf();
    const double a = std::abs(H(0, 0));  // sum of the PSF (> 0)
    const double inv_n = 1.0 / (static_cast<double>(R) * W);
    // H / a and conj(H) / a with the inverse transform's 1/N folded in.
    S hs(R, hc), hcs(R, hc);
    for (Eigen::Index i = 0; i < H.size(); ++i) {
        const std::complex<double> h = H.data()[i] * (inv_n / a);
        hs.data()[i] = Cx(h);
        hcs.data()[i] = Cx(std::conj(h));
    }
    const double p_max = p_d.maxCoeff();
    const T ax_floor = static_cast<T>(kRlTiny * std::max(p_max, 1e-300));
    if (!std::is_same_v<T, double>) {
        const double mag = std::max(p_max, a * x_io.abs().maxCoeff());
        if (!fits_single_precision(mag)) {
            throw invalid_field("single_precision", "true",
                                "Richardson-Lucy's values reach " + std::to_string(mag) +
                                    ", beyond float32's safe range: run it in double");
        }
    }
    const P p = p_d.cast<T>();
    const P inv_at1 = (inv_at1_d * a).cast<T>();
    P x = (x_io * a).cast<T>();
    P work(R, W), back(R, W), ratio;
    if (linear) {
        ratio = P::Zero(R, W);  // C^T (p / A x): zero outside the capture window
    } else {
        ratio.resize(R, W);
    }
    S spec(R, hc);
    auto apply_a = [&] {  // work = H x (uncropped)
        fft.forward(x, spec);
        spec *= hs;
        fft.inverse_unscaled_destroy(spec, work);
    };
    auto crop_ax = [&] { return Plane(work.block(cr, cc, pr, pc).template cast<double>()); };
    apply_a();
    r.converged = false;
    for (int k = 1; k <= o.max_iterations; ++k) {
        for (int i = 0; i < pr; ++i) {
            const T* __restrict wrow = work.data() + Eigen::Index(cr + i) * W + cc;
            const T* __restrict prow = p.data() + Eigen::Index(i) * pc;
            T* __restrict q =
                ratio.data() + Eigen::Index(linear ? cr + i : i) * W + (linear ? cc : 0);
            for (int c = 0; c < pc; ++c) {
                q[c] = prow[c] > T(0) ? prow[c] / std::max(wrow[c], ax_floor) : T(0);
            }
        }
        fft.forward(ratio, spec);
        spec *= hcs;
        fft.inverse_unscaled_destroy(spec, back);
        {  // x <- max(0, x A^T(ratio) / A^T 1); back <- the change of x (for the stopping rule)
            T* __restrict xq = x.data();
            T* __restrict bq = back.data();
            const T* __restrict iq = inv_at1.data();
            for (Eigen::Index i = 0; i < x.size(); ++i) {
                const T xo = xq[i];
                const T xn = std::max(T(0), xo * bq[i] * iq[i]);  // FFT rounding can dip below 0
                xq[i] = xn;
                bq[i] = xn - xo;
            }
        }
        apply_a();
        r.iterations = k;
        // relative_change(x, x_old) of solver_common (0 / 0 = 0, d / 0 = inf) by Eigen's
        // vectorised reductions; tolerance 0 never stops on it (a moving x never met <= 0).
        double change = std::numeric_limits<double>::infinity();
        if (o.tolerance > 0.0) {
            const double diff2 = back.template cast<double>().square().sum();
            const double norm2 = x.template cast<double>().square().sum();
            change = norm2 > 0.0 ? std::sqrt(diff2 / norm2) : (diff2 > 0.0 ? change : 0.0);
        }
        if (o.record_history) {  // i_divergence and the residual of A x, read in place
            const double floor = kRlTiny * std::max(p_max, 1e-300);
            double div = 0.0, res2 = 0.0;
            for (int i = 0; i < pr; ++i) {
                const T* wrow = work.data() + Eigen::Index(cr + i) * W + cc;
                for (int c = 0; c < pc; ++c) {
                    const double q = double(wrow[c]), pi = p_d(i, c), qf = std::max(q, floor);
                    div += (pi > 0.0 ? pi * std::log(pi / qf) : 0.0) - pi + qf;
                    const double e = q - capture(i, c);
                    res2 += e * e;
                }
            }
            IterationRecord rec;
            rec.iteration = k;
            rec.objective = div;
            rec.residual = std::sqrt(res2);
            rec.seconds = clock.seconds();
            r.history.push_back(rec);
        }
        if (iteration_ends(change <= o.tolerance, o, r)) break;
    }
    x_io = x.template cast<double>() / a;
    ax_out = crop_ax();
}

}  // namespace

DecodeResult solve_richardson_lucy(const ConvolutionOperator& op, const Plane& psf,
                                   const Plane& capture, const RichardsonLucyOptions& o,
                                   const Plane* warm_start) {
    const SolverClock clock;
    const ConvGeometry& g = op.geometry();
    validate_iterative_options(o);
    if (capture.rows() != g.capture_rows || capture.cols() != g.capture_cols) {
        throw invalid_field("capture",
                            std::to_string(capture.rows()) + " x " + std::to_string(capture.cols()),
                            "must match the operator's capture size");
    }
    if ((psf < 0.0).any()) {
        throw invalid_field("psf", "min " + std::to_string(psf.minCoeff()),
                            "Richardson-Lucy needs a non-negative PSF");
    }
    if (warm_start) check_warm_start(*warm_start, g);

    const Plane p = capture.max(0.0);
    const Plane at1 = op.adjoint(Plane::Ones(g.capture_rows, g.capture_cols));
    const double at1_floor = kRlTiny * at1.maxCoeff();
    const Plane inv_at1 = (at1 > at1_floor).select(1.0 / at1.max(at1_floor), 0.0);

    Plane x = warm_start ? Plane(warm_start->max(0.0))
                         : Plane::Constant(g.work_rows, g.work_cols, p.mean() / psf.sum());
    x *= (inv_at1 > 0.0).cast<double>();

    DecodeResult r;
    Plane ax;
    if (o.single_precision) {
        iterate<float>(op, p, capture, inv_at1, o, x, ax, r, clock);
    } else {
        iterate<double>(op, p, capture, inv_at1, o, x, ax, r, clock);
    }
    if (o.max_iterations == 0) r.converged = true;
    r.objective = i_divergence(p, ax);
    r.residual = std::sqrt((ax - capture).square().sum());
    r.image = std::move(x);
    r.seconds = clock.seconds();
    return r;
}

}  // namespace pinmask
