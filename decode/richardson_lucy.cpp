#include "decode/richardson_lucy.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

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
    const double p_max = p.maxCoeff();
    const double ax_floor = kRlTiny * std::max(p_max, 1e-300);
    const Plane at1 = op.adjoint(Plane::Ones(g.capture_rows, g.capture_cols));
    const double at1_floor = kRlTiny * at1.maxCoeff();
    const Plane inv_at1 = (at1 > at1_floor).select(1.0 / at1.max(at1_floor), 0.0);

    Plane x = warm_start ? Plane(warm_start->max(0.0))
                         : Plane::Constant(g.work_rows, g.work_cols, p.mean() / psf.sum());
    x *= (inv_at1 > 0.0).cast<double>();

    // A x and A^T y on reused buffers (no allocation inside the loop).
    const Fft2& fft = op.fft();
    const ComplexPlane& H = op.otf();
    const ComplexPlane Hc = H.conjugate();
    const int cr = g.crop_row, cc = g.crop_col, pr = g.capture_rows, pc = g.capture_cols;
    const bool linear = g.model == ConvModel::kLinear;
    ComplexPlane spec, scratch;
    Plane work, ratio(pr, pc), pad_buf, back, x_old(x.rows(), x.cols());
    if (linear) pad_buf = Plane::Zero(g.work_rows, g.work_cols);
    Plane ax(pr, pc);
    auto apply_a = [&] {
        fft.forward(x, spec);
        spec *= H;
        fft.inverse(spec, work, scratch);
        ax = work.block(cr, cc, pr, pc);
    };
    apply_a();
    DecodeResult r;
    r.converged = false;
    for (int k = 1; k <= o.max_iterations; ++k) {
        ratio = (p > 0.0).select(p / ax.max(ax_floor), 0.0);
        if (linear) {
            pad_buf.block(cr, cc, pr, pc) = ratio;
            fft.forward(pad_buf, spec);
        } else {
            fft.forward(ratio, spec);
        }
        spec *= Hc;
        fft.inverse(spec, back, scratch);
        x_old.swap(x);
        x = (x_old * back * inv_at1).max(0.0);  // FFT rounding can dip below 0
        apply_a();
        r.iterations = k;
        const double change = relative_change(x, x_old);
        if (o.record_history) {
            IterationRecord rec;
            rec.iteration = k;
            rec.objective = i_divergence(p, ax);
            rec.residual = std::sqrt((ax - capture).square().sum());
            rec.seconds = clock.seconds();
            r.history.push_back(rec);
        }
        if (iteration_ends(change <= o.tolerance, o, r)) break;
    }
    if (o.max_iterations == 0) r.converged = true;
    r.objective = i_divergence(p, ax);
    r.residual = std::sqrt((ax - capture).square().sum());
    r.image = std::move(x);
    r.seconds = clock.seconds();
    return r;
}

}  // namespace pinmask
