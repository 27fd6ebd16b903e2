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
// Below this adaptivity the balance is left alone (saves its extra FFT pair per iteration).
constexpr double kAlphaStop = 1e-3;
constexpr double kDelta = 1.5;
// |H| below this fraction of max|H| counts as a spectral zero in the pseudo-inverse.
constexpr double kPinvRelThreshold = 1e-10;
// tau = sigma = 0.99 initially: strictly inside tau sigma < 1 (preconditioned, norm <= 1).
constexpr double kStepSafety = 0.99;

double norm2(const Plane& a) { return std::sqrt(a.square().sum()); }

// sum_k |S_k|^2 over the full spectrum of a real plane with `cols` columns, from its half
// spectrum (columns 1 .. ceil(cols / 2) - 1 stand for two columns each).
double half_spectrum_energy(const ComplexPlane& half, int cols) {
    const Eigen::Index hc = half.cols();
    double e = 2.0 * half.abs2().sum() - half.col(0).abs2().sum();
    if (cols % 2 == 0 && hc > 1) e -= half.col(hc - 1).abs2().sum();
    return e;
}

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

// Bisection steps in log lambda over kLambdaDecades decades around mean |H|^2 (resolution
// 24 / 2^16 decades), and the fraction of eps the starting point's residual aims at.
constexpr int kLambdaBisections = 16;
constexpr double kLambdaDecades = 12.0;  // each side of mean |H|^2
constexpr double kStartResidualFraction = 0.99;

struct FeasiblePoint {
    Plane x;
    Plane residual;  // A x - p
    double norm = 0.0;
};

// x_lambda = IFFT[conj(H) P / (|H|^2 + lambda |D|^2)] (0 where the denominator is 0) with the
// largest lambda whose residual ||A x - p|| is <= kStartResidualFraction eps: feasible, and as
// smooth as a quadratic-gradient estimate allows. Returns the lambda = 0 estimate when even that
// misses the target (the problem may then be infeasible) and the constant estimate when it fits.
FeasiblePoint smooth_feasible_point(const ConvolutionOperator& op, const Plane& capture,
                                    double eps) {
    const ConvGeometry& g = op.geometry();
    const Fft2& fft = op.fft();
    const ComplexPlane& H = op.otf();
    const ComplexPlane hp = H.conjugate() * fft.forward(pad_to_work(g, capture));
    const Plane h2 = H.abs2();
    const Plane gram = gradient_gram_symbol(g.work_rows, g.work_cols);
    ComplexPlane spec(H.rows(), H.cols()), scratch;
    Plane work;
    auto solve = [&](double lambda, FeasiblePoint& f) {
        for (Eigen::Index i = 0; i < spec.size(); ++i) {
            const double d = h2.data()[i] + lambda * gram.data()[i];
            spec.data()[i] = d > 0.0 ? hp.data()[i] / d : 0.0;
        }
        fft.inverse(ComplexPlane(H * spec), work, scratch);
        f.residual = crop_to_capture(g, work) - capture;
        f.norm = norm2(f.residual);
    };
    const double target = kStartResidualFraction * eps;
    const double mid = std::log10(std::max(h2.mean(), 1e-300));
    double lo = mid - kLambdaDecades, hi = mid + kLambdaDecades;
    FeasiblePoint best, trial;
    solve(std::pow(10.0, hi), trial);
    double chosen = std::pow(10.0, hi);
    if (trial.norm <= target) {
        best = std::move(trial);
    } else {
        solve(0.0, best);
        chosen = 0.0;
        if (best.norm <= target) {
            for (int i = 0; i < kLambdaBisections; ++i) {
                const double m = 0.5 * (lo + hi);
                solve(std::pow(10.0, m), trial);
                if (trial.norm <= target) {
                    lo = m;
                    chosen = std::pow(10.0, m);
                    std::swap(best, trial);
                } else {
                    hi = m;
                }
            }
        }
    }
    solve(chosen, trial);  // recompute the spectrum of the chosen estimate
    fft.inverse(spec, best.x, scratch);
    best.residual = std::move(trial.residual);
    best.norm = trial.norm;
    return best;
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
    const bool nn = o.nonnegative;
    // Block weights: beta for A, gamma for I. beta = sqrt(8) / rms|H| puts the typical gain of
    // beta A at the gradient's bound sqrt 8, so the two dual blocks have comparable scales (the
    // preconditioner below makes convergence hold for any beta; this choice makes it fast).
    const double beta = std::sqrt(8.0) / std::sqrt(std::max(H.abs2().mean(), 1e-300));
    const double gamma = nn ? 1.0 : 0.0;
    // Fourier-diagonal preconditioner T = M^-1, M = grad^T grad + beta^2 H^* H + gamma^2 I >=
    // K^T K (C^T C <= I), so ||K M^-1/2|| <= 1 and tau sigma < 1 suffices.
    const Plane m_inv = 1.0 / (gradient_gram_symbol(g.work_rows, g.work_cols) +
                               beta * beta * H.abs2() + gamma * gamma)
                                  .max(1e-300);
    double tau = kStepSafety, sigma = kStepSafety, alpha = kAlpha0;
    const Plane center = beta * capture;
    const double radius = beta * eps;
    const ComplexPlane beta_hc = beta * H.conjugate();
    const bool linear = g.model == ConvModel::kLinear;
    const int cr = g.crop_row, cc = g.crop_col, pr = g.capture_rows, pc = g.capture_cols;

    ComplexPlane spec, spec2, scratch;
    Plane work, pad_buf;
    if (linear) pad_buf = Plane::Zero(g.work_rows, g.work_cols);
    auto apply_a = [&](const Plane& x, Plane& out) {  // out = A x
        fft.forward(x, spec);
        spec *= H;
        fft.inverse(spec, work, scratch);
        out = work.block(cr, cc, pr, pc);
    };

    const FeasiblePoint start =
        eps > 0.0 ? smooth_feasible_point(op, capture, eps) : FeasiblePoint{};
    Plane x = warm_start  ? *warm_start
              : eps > 0.0 ? start.x
                          : Plane::Zero(g.work_rows, g.work_cols);
    // K x = (grad x, beta A x, gamma x), cached as grad x and A x (the gamma block is x).
    Plane kx_r, kx_c, ax;
    gradient(x, kx_r, kx_c);
    apply_a(x, ax);
    Plane y_r = Plane::Zero(g.work_rows, g.work_cols), y_c = y_r, y_w;
    Plane y_q = Plane::Zero(pr, pc);
    if (nn) y_w = Plane::Zero(g.work_rows, g.work_cols);

    // Buffers reused by every iteration (no allocation inside the loop).
    Plane x_new(g.work_rows, g.work_cols), dx, nr, nc, yr_new(x_new), yc_new(x_new), yw_new;
    Plane ax_new(pr, pc), v(pr, pc);
    if (nn) yw_new.resize(g.work_rows, g.work_cols);
    double dres_prev = -1.0;  // dual residual of the previous iteration (< 0: none yet)
    r.converged = false;
    for (int k = 1; k <= o.max_iterations; ++k) {
        // K^T y in Fourier space: F[-div y1 + gamma y_w] + beta conj(H) F[C^T y_q].
        divergence(y_r, y_c, work);  // K^T y = -(div y1 - gamma y_w) + ...
        if (nn) work -= gamma * y_w;
        fft.forward(work, spec2);
        if (linear) {
            pad_buf.block(cr, cc, pr, pc) = y_q;
            fft.forward(pad_buf, spec);
        } else {
            fft.forward(y_q, spec);
        }
        spec2 = beta_hc * spec - spec2;

        // Adaptive balance of tau and sigma (product constant), Goldstein et al.: the primal
        // residual is K^T y (G = 0; its norm by Parseval), the dual residual comes from the
        // previous dual step.
        if (alpha > kAlphaStop && dres_prev >= 0.0) {
            const double pres =
                std::sqrt(half_spectrum_energy(spec2, g.work_cols) / double(x.size()));
            if (pres > kDelta * dres_prev) {
                tau /= 1.0 - alpha;
                sigma *= 1.0 - alpha;
                alpha *= kEta;
            } else if (pres < dres_prev / kDelta) {
                tau *= 1.0 - alpha;
                sigma /= 1.0 - alpha;
                alpha *= kEta;
            }
        }

        // Primal step x_new = x - tau M^-1 K^T y, and A x_new from the same spectrum.
        spec2 *= m_inv.cast<std::complex<double>>();
        fft.inverse(spec2, dx, scratch);
        spec2 *= H;
        fft.inverse(spec2, work, scratch);
        double x_new_norm2 = 0.0, step_norm2 = 0.0;
        for (Eigen::Index i = 0; i < x.size(); ++i) {
            const double d = tau * dx.data()[i];
            const double xn = x.data()[i] - d;
            x_new.data()[i] = xn;
            x_new_norm2 += xn * xn;
            step_norm2 += d * d;
        }
        ax_new = ax - tau * work.block(cr, cc, pr, pc);
        const double change = step_norm2 == 0.0 ? 0.0 : std::sqrt(step_norm2 / x_new_norm2);
        gradient(x_new, nr, nc);

        // Dual step at xbar = 2 x_new - x, K xbar from the cached K x; the gradient block and
        // its share of the dual residual in one pass.
        double d2 = 0.0;
        for (Eigen::Index i = 0; i < x.size(); ++i) {
            const double kr = kx_r.data()[i], kc = kx_c.data()[i];
            const double gr = nr.data()[i], gc = nc.data()[i];
            const double yr = y_r.data()[i], yc = y_c.data()[i];
            double ar = yr + sigma * (2.0 * gr - kr), ac = yc + sigma * (2.0 * gc - kc);
            const double scale = std::max(1.0, std::sqrt(ar * ar + ac * ac));
            ar /= scale;
            ac /= scale;
            yr_new.data()[i] = ar;
            yc_new.data()[i] = ac;
            const double er = (yr - ar) / sigma - (kr - gr), ec = (yc - ac) / sigma - (kc - gc);
            d2 += er * er + ec * ec;
        }
        // proj_B(v / sigma) = center + z min(1, radius / |z|) with z = v / sigma - center, so
        // v - sigma proj_B(v / sigma) = (1 - min(1, radius / |z|)) (v - sigma center).
        v = y_q + (sigma * beta) * (2.0 * ax_new - ax);
        const double zn = std::sqrt((v / sigma - center).square().sum());
        const double keep = zn > radius ? 1.0 - radius / zn : 0.0;
        v = keep * (v - sigma * center);
        d2 += ((y_q - v) / sigma - beta * (ax - ax_new)).square().sum();
        if (nn) {
            yw_new = (y_w + (sigma * gamma) * (2.0 * x_new - x)).min(0.0);
            d2 += ((y_w - yw_new) / sigma - gamma * (x - x_new)).square().sum();
        }
        dres_prev = std::sqrt(d2);

        x.swap(x_new);
        ax.swap(ax_new);
        kx_r.swap(nr);
        kx_c.swap(nc);
        y_r.swap(yr_new);
        y_c.swap(yc_new);
        y_q.swap(v);
        if (nn) y_w.swap(yw_new);

        const double res = norm2(ax - capture);
        const double viol = std::max(res - eps, 0.0) + (nn ? norm2(x.min(0.0)) : 0.0);
        r.iterations = k;
        if (o.record_history) {
            IterationRecord rec;
            rec.iteration = k;
            rec.objective = total_variation(kx_r, kx_c);
            rec.residual = relative_residual(res);
            rec.seconds = clock.seconds();
            r.history.push_back(rec);
        }
        // k >= 2: the first primal step starts from y = 0 and does not move x.
        const bool converged =
            k >= 2 && change <= o.tolerance && viol <= o.tolerance * std::max(eps, p_norm);
        if (iteration_ends(converged, o, r)) break;
    }
    if (o.max_iterations == 0) r.converged = true;

    // Feasibility restoration: eps > 0, the smallest step towards the feasible smooth point
    // (TV convex: TV rises by at most t (TV(x_f) - TV(x))); eps = 0, the pseudo-inverse
    // correction (the orthogonal projection on A x = p for the cyclic model).
    if (nn) x = x.max(0.0);  // x >= 0 is a dual block: exact only in the limit
    apply_a(x, ax);
    Plane res_x = ax - capture;
    if (norm2(res_x) > eps) {
        Plane delta, a_delta;
        if (eps > 0.0) {
            delta = start.x - x;
            a_delta = start.residual - res_x;
        } else {
            const double thr = kPinvRelThreshold * op.otf_max_abs();
            fft.forward(pad_to_work(g, Plane(-res_x)), spec);
            for (Eigen::Index i = 0; i < spec.size(); ++i) {
                const std::complex<double> h = H.data()[i];
                spec.data()[i] = std::abs(h) > thr ? spec.data()[i] / h : 0.0;
            }
            fft.inverse(spec, delta, scratch);
            apply_a(delta, a_delta);
        }
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
    if (r.residual - eps > kTvqcFeasibilityTol * std::max(eps, p_norm)) {
        r.converged = false;
        r.constraint_met = false;
    }
    r.image = std::move(x);
    r.objective = total_variation(r.image);
    r.seconds = clock.seconds();
    return r;
}

}  // namespace pinmask
