#include "decode/tvqc.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "decode/gradient.hpp"

namespace pinmask {
namespace {

// Adaptive PDHG constants (Goldstein, Li, Yuan 2015): initial adaptivity, its decay, the
// residual ratio that triggers a change, and the residual scale.
constexpr double kAlpha0 = 0.5;
constexpr double kEta = 0.95;
constexpr double kDelta = 1.5;
// |H| below this fraction of max|H| counts as a spectral zero in the pseudo-inverse.
constexpr double kPinvRelThreshold = 1e-10;
// 0.99 / L: strictly inside tau sigma L^2 < 1.
constexpr double kStepSafety = 0.99;

double norm2(const Plane& a) { return std::sqrt(a.square().sum()); }

// Smallest t in [0, 1] with ||r + t d|| <= eps, or the t in [0, 1] minimising ||r + t d||.
double feasibility_step(const Plane& r, const Plane& d, double eps) {
    const double a = d.square().sum(), b = (r * d).sum(), c = r.square().sum() - eps * eps;
    if (c <= 0.0) return 0.0;
    if (!(a > 0.0)) return 0.0;
    const double disc = b * b - a * c;
    if (disc < 0.0 || b >= 0.0) return std::clamp(-b / a, 0.0, 1.0);  // no crossing
    const double t = c / (-b + std::sqrt(disc));  // smaller root, cancellation-free
    return t <= 1.0 ? t : std::clamp(-b / a, 0.0, 1.0);
}

}  // namespace

double tvqc_eps_from_sigma(double noise_sigma, long long n) {
    if (!(noise_sigma >= 0.0) || !std::isfinite(noise_sigma)) {
        throw invalid_field("noise_sigma", std::to_string(noise_sigma), "must be finite and >= 0");
    }
    if (n < 1) throw invalid_field("n_measurements", std::to_string(n), "must be >= 1");
    const double N = static_cast<double>(n);
    return noise_sigma * std::sqrt(N) * std::sqrt(1.0 + 2.0 * std::sqrt(2.0 / N));
}

DecodeResult solve_tvqc(const ConvolutionOperator& op, const Plane& capture, const TvqcOptions& o,
                        const Plane* warm_start) {
    const SolverClock clock;
    const ConvGeometry& g = op.geometry();
    validate_iterative_options(o);
    if (capture.rows() != g.capture_rows || capture.cols() != g.capture_cols) {
        throw invalid_field("capture",
                            std::to_string(capture.rows()) + " x " + std::to_string(capture.cols()),
                            "must match the operator's capture size");
    }
    if (!(o.eps >= 0.0) || !std::isfinite(o.eps)) {
        throw invalid_field("eps", std::to_string(o.eps), "must be finite and >= 0");
    }
    if (warm_start) check_warm_start(*warm_start, g);

    DecodeResult r;
    const double p_norm = norm2(capture);
    const double eps = o.eps;
    auto relative_residual = [&](double res) {
        return eps > 0.0 ? res / eps : (p_norm > 0.0 ? res / p_norm : res);
    };
    if (eps >= p_norm) {  // x = 0 is feasible and has TV = 0
        r.image = Plane::Zero(g.work_rows, g.work_cols);
        r.residual = p_norm;
        r.objective = 0.0;
        r.converged = true;
        r.seconds = clock.seconds();
        return r;
    }

    const Fft2& fft = op.fft();
    const ComplexPlane& H = op.otf();
    const double beta = std::sqrt(8.0) / op.otf_max_abs();
    const double L = 4.0;  // sqrt(8 + beta^2 max|H|^2)
    double tau = kStepSafety / L, sigma = kStepSafety / L, alpha = kAlpha0;
    const Plane center = beta * capture;
    const double radius = beta * eps;

    ComplexPlane spec, scratch;
    Plane work;
    // A x and A^T y through the cached spectra.
    auto apply_a = [&](const Plane& x, Plane& out) {
        fft.forward(x, spec);
        spec *= H;
        fft.inverse(spec, work, scratch);
        out = crop_to_capture(g, work);
    };
    auto apply_at = [&](const Plane& y, Plane& out) {
        fft.forward(pad_to_work(g, y), spec);
        spec *= H.conjugate();
        fft.inverse(spec, out, scratch);
    };

    Plane x = warm_start ? *warm_start : Plane::Zero(g.work_rows, g.work_cols);
    if (o.nonnegative) x = x.max(0.0);
    Plane kx_r, kx_c, kx_q;  // K x
    gradient(x, kx_r, kx_c);
    apply_a(x, kx_q);
    kx_q *= beta;
    Plane y_r = Plane::Zero(g.work_rows, g.work_cols), y_c = y_r;
    Plane y_q = Plane::Zero(g.capture_rows, g.capture_cols);
    Plane kty = Plane::Zero(g.work_rows, g.work_cols);  // K^T y

    Plane x_new, nr, nc, nq, atq, kty_new;
    r.converged = false;
    for (int k = 1; k <= o.max_iterations; ++k) {
        // Primal step.
        x_new = x - tau * kty;
        if (o.nonnegative) x_new = x_new.max(0.0);
        gradient(x_new, nr, nc);
        apply_a(x_new, nq);
        nq *= beta;
        // Dual step at xbar = 2 x_new - x (K xbar from the cached K x).
        Plane yr_new = y_r + sigma * (2.0 * nr - kx_r);
        Plane yc_new = y_c + sigma * (2.0 * nc - kx_c);
        const Plane scale = (yr_new.square() + yc_new.square()).sqrt().max(1.0);
        yr_new /= scale;
        yc_new /= scale;
        Plane v = y_q + sigma * (2.0 * nq - kx_q);
        {
            Plane z = v / sigma - center;  // proj_B(v / sigma) = center + z min(1, radius/|z|)
            const double zn = norm2(z);
            if (zn > radius) z *= (zn > 0.0 ? radius / zn : 0.0);
            v -= sigma * (center + z);
        }
        apply_at(v, atq);
        kty_new = -divergence(yr_new, yc_new) + beta * atq;

        // Adaptive step balance (tau sigma constant).
        const double pres = norm2((x - x_new) / tau - (kty - kty_new));
        const double dres = std::sqrt(((y_r - yr_new) / sigma - (kx_r - nr)).square().sum() +
                                      ((y_c - yc_new) / sigma - (kx_c - nc)).square().sum() +
                                      ((y_q - v) / sigma - (kx_q - nq)).square().sum());
        if (pres > kDelta * dres) {
            tau /= 1.0 - alpha;
            sigma *= 1.0 - alpha;
            alpha *= kEta;
        } else if (pres < dres / kDelta) {
            tau *= 1.0 - alpha;
            sigma /= 1.0 - alpha;
            alpha *= kEta;
        }

        const double change = relative_change(x_new, x);
        x.swap(x_new);
        kx_r.swap(nr);
        kx_c.swap(nc);
        kx_q.swap(nq);
        y_r.swap(yr_new);
        y_c.swap(yc_new);
        y_q.swap(v);
        kty.swap(kty_new);

        const double res = norm2(kx_q / beta - capture);
        r.iterations = k;
        if (o.record_history) {
            IterationRecord rec;
            rec.iteration = k;
            rec.objective = total_variation(kx_r, kx_c);
            rec.residual = relative_residual(res);
            rec.seconds = clock.seconds();
            r.history.push_back(rec);
        }
        if (change <= o.tolerance && res - eps <= o.tolerance * std::max(eps, p_norm)) {
            r.converged = true;
            break;
        }
    }
    if (o.max_iterations == 0) r.converged = true;

    // Feasibility restoration along the pseudo-inverse correction.
    Plane ax;
    apply_a(x, ax);
    Plane res_x = ax - capture;
    if (norm2(res_x) > eps) {
        const double thr = kPinvRelThreshold * op.otf_max_abs();
        fft.forward(pad_to_work(g, Plane(-res_x)), spec);
        for (Eigen::Index i = 0; i < spec.size(); ++i) {
            const std::complex<double> h = H.data()[i];
            spec.data()[i] = std::abs(h) > thr ? spec.data()[i] / h : 0.0;
        }
        Plane delta, a_delta;
        fft.inverse(spec, delta, scratch);
        apply_a(delta, a_delta);
        const double t = feasibility_step(res_x, a_delta, eps);
        if (t > 0.0) {
            Plane x_fix = x + t * delta;
            if (!o.nonnegative || (x_fix >= 0.0).all()) {
                x.swap(x_fix);
                apply_a(x, ax);
                res_x = ax - capture;
            }
        }
    }
    r.residual = norm2(res_x);
    if (r.residual - eps > kTvqcFeasibilityTol * std::max(eps, p_norm)) r.converged = false;
    r.image = std::move(x);
    r.objective = total_variation(r.image);
    r.seconds = clock.seconds();
    return r;
}

}  // namespace pinmask
