#include "decode/solvers/tvqc.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "core/errors/error.hpp"
#include "decode/solvers/gradient.hpp"
#include "decode/solvers/precision.hpp"

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

// One row of the dual step of the gradient block (pdhg's dual_row): y1 <- the projection on the
// unit ball of y1 + sigma grad xbar, xbar = x_new - d, with periodic forward differences (x, d:
// this row; xd, dd: the row below; the last column's right neighbour is the row's first pixel).
// Per pixel it stores the squared dual residual (y_old - y_new) / sigma - grad(x_old - x_new) in
// e and, with kTv, |grad x_new| in tv; no reduction, and every pointer restrict, so the column
// loop vectorises. Not inlined: inlined into pdhg's row loop, GCC 12 drops the restrict
// qualifiers, needs more run-time alias checks than it allows and kept the loop scalar (the
// projection's max and division one pixel at a time: a quarter of a linear-model iteration).
template <class T, bool kTv>
inline __attribute__((always_inline)) void dual_point(const T* __restrict x, const T* __restrict xd,
                                                      const T* __restrict d, const T* __restrict dd,
                                                      T* __restrict yr, T* __restrict yc,
                                                      T* __restrict e, T* __restrict tv, int c,
                                                      int rt, T st, T inv_s) {
    const T gr = xd[c] - x[c], gc = x[rt] - x[c];
    const T sr = dd[c] - d[c], sc = d[rt] - d[c];  // grad of the step
    const T yro = yr[c], yco = yc[c];
    const T ar = yro + st * (gr - sr), ac = yco + st * (gc - sc);
    const T f = T(1) / std::max(T(1), std::sqrt(ar * ar + ac * ac));
    const T nr = ar * f, nc = ac * f;
    yr[c] = nr;
    yc[c] = nc;
    const T er = (yro - nr) * inv_s - sr, ec = (yco - nc) * inv_s - sc;
    e[c] = er * er + ec * ec;
    if constexpr (kTv) tv[c] = std::sqrt(gr * gr + gc * gc);
}

template <class T, bool kTv>
__attribute__((noinline)) void dual_row_points(const T* __restrict x, const T* __restrict xd,
                                               const T* __restrict d, const T* __restrict dd,
                                               T* __restrict yr, T* __restrict yc, T* __restrict e,
                                               T* __restrict tv, int W, T st, T inv_s) {
    for (int c = 0; c + 1 < W; ++c)
        dual_point<T, kTv>(x, xd, d, dd, yr, yc, e, tv, c, c + 1, st, inv_s);
    dual_point<T, kTv>(x, xd, d, dd, yr, yc, e, tv, W - 1, 0, st, inv_s);
}

// Block weights: beta for A (beta = sqrt(8) / rms|H| puts the typical gain of beta A at the
// gradient's bound sqrt 8, so the two dual blocks have comparable scales; the preconditioner
// makes convergence hold for any beta, this choice makes it fast), gamma for I.
double tvqc_beta(const ComplexPlane& H) {
    return std::sqrt(8.0) / std::sqrt(std::max(H.abs2().mean(), 1e-300));
}

// The iteration in precision T from x (working grid, double, updated in place), fused loops on
// raw arrays (see the header): per iteration two forward transforms, one spectral pass, two
// inverse transforms, one pass over the working grid and two over the capture window. The data
// block is held as beta A x and beta p (beta H has rms sqrt 8: float-safe whatever the PSF's
// scale). Every buffer is allocated before the first iteration; sums are in double.
template <class T>
void pdhg(const ConvolutionOperator& op, const Plane& capture, const TvqcOptions& o, double p_norm,
          Plane& x_io, DecodeResult& r, const SolverClock& clock) {
    using Types = PrecisionTypes<T>;
    using P = typename Types::Plane;
    using S = typename Types::Spectrum;
    using Cx = std::complex<T>;
    const ConvGeometry& g = op.geometry();
    const int R = g.work_rows, W = g.work_cols, hc = W / 2 + 1;
    const int cr = g.crop_row, cc = g.crop_col, pr = g.capture_rows, pc = g.capture_cols;
    const bool linear = g.model == ConvModel::kLinear;
    const bool nn = o.nonnegative;
    const double eps = o.eps;
    const typename Types::Fft fft(R, W);
    const ComplexPlane& H = op.otf();
    const double beta = tvqc_beta(H);
    const double gamma = nn ? 1.0 : 0.0;
    const double radius = beta * eps;
    const Plane ax0 = op.apply(x_io);
    if (!std::is_same_v<T, double>) {
        const double mag = std::max(
            {beta * capture.abs().maxCoeff(), beta * ax0.abs().maxCoeff(), x_io.abs().maxCoeff()});
        if (!fits_single_precision(mag)) {
            throw invalid_field("single_precision", "true",
                                "TVQC's iterates reach " + std::to_string(mag) +
                                    ", beyond float32's safe range: run it in double");
        }
    }

    // Spectral constants with the inverse transform's 1/N folded in: M^-1 / N and beta H.
    // M = grad^T grad + beta^2 |H|^2 + gamma^2 >= K^T K (C^T C <= I), so ||K M^-1/2|| <= 1.
    const double inv_n = 1.0 / (static_cast<double>(R) * W);
    const Plane gram = gradient_gram_symbol(R, W);
    const Eigen::Index nh = Eigen::Index(R) * hc;
    P m_inv(R, hc);
    S bh(R, hc);
    for (Eigen::Index i = 0; i < nh; ++i) {
        const std::complex<double> h = H.data()[i];
        const double m =
            1.0 / std::max(gram.data()[i] + beta * beta * std::norm(h) + gamma * gamma, 1e-300);
        m_inv.data()[i] =
            static_cast<T>(std::min(m * inv_n, double(std::numeric_limits<T>::max())));
        bh.data()[i] = Cx(beta * h);
    }

    P x = x_io.cast<T>();
    P dx(R, W), aw(R, W), kty = P::Zero(R, W);  // kty = grad^T y1 + gamma y_w (spatial K^T y)
    P yr = P::Zero(R, W), yc = P::Zero(R, W), yw;
    if (nn) yw = P::Zero(R, W);
    P bax = (beta * ax0).cast<T>(), bp = (beta * capture).cast<T>(), yq = P::Zero(pr, pc);
    P pad;
    if (linear) pad = P::Zero(R, W);
    S spec(R, hc), spec2(R, hc), spec3(R, hc);
    // Row buffers of the per-pixel terms of the sums: the loops store them (no reduction, so
    // they vectorise) and Eigen sums each row in double (its vectorised reduction).
    using Row = Eigen::Array<T, Eigen::Dynamic, 1>;
    const int row_len = std::max(W, pc);
    Row row_e(row_len), row_tv(row_len), row_a(row_len), row_b(row_len);
    auto row_sum = [](const Row& row, int len) {
        return row.head(len).template cast<double>().sum();
    };
    T* const xp = x.data();
    T* const dp = dx.data();
    T* const yrp = yr.data();
    T* const ycp = yc.data();
    T* const ywp = nn ? yw.data() : nullptr;
    T* const kp = kty.data();

    double tau = kStepSafety, sigma = kStepSafety, alpha = kAlpha0;
    double dres_prev = -1.0;  // dual residual of the previous iteration (< 0: none yet)
    auto relative_residual = [&](double res) {
        return eps > 0.0 ? res / eps : (p_norm > 0.0 ? res / p_norm : res);
    };
    r.converged = false;
    for (int k = 1; k <= o.max_iterations; ++k) {
        // F[K^T y] = F[grad^T y1 + gamma y_w] + conj(beta H) F[C^T y_q].
        fft.forward(kty, spec2);
        if (linear) {
            pad.block(cr, cc, pr, pc) = yq;
            fft.forward(pad, spec);
        } else {
            fft.forward(yq, spec);
        }
        // One spectral pass: K^T y, its energy for the step balance (Parseval, half spectrum
        // with multiplicity), M^-1 K^T y / N and beta H M^-1 K^T y / N.
        const bool adapt = alpha > kAlphaStop && dres_prev >= 0.0;
        double energy = 0.0;
        for (int kr = 0; kr < R; ++kr) {
            T* __restrict eq = row_e.data();
            for (int l = 0; l < hc; ++l) {
                const Eigen::Index i = Eigen::Index(kr) * hc + l;
                // Complex products written out: std::complex's operator* calls __muldc3 (the
                // C99 Inf/NaN rules), which costs more than the rest of the pass.
                const T br = bh.data()[i].real(), bi = bh.data()[i].imag();
                const T sr = spec.data()[i].real(), si = spec.data()[i].imag();
                const T ktr = br * sr + bi * si + spec2.data()[i].real();  // conj(b) s + K1^T y
                const T kti = br * si - bi * sr + spec2.data()[i].imag();
                eq[l] = ktr * ktr + kti * kti;
                const T m = m_inv.data()[i];
                const T qr = ktr * m, qi = kti * m;
                spec2.data()[i] = Cx(qr, qi);
                spec3.data()[i] = Cx(qr * br - qi * bi, qr * bi + qi * br);
            }
            if (adapt) {  // Parseval on the half spectrum: columns 1 .. ceil(W / 2) - 1 twice
                energy += 2.0 * row_sum(row_e, hc) - double(eq[0]);
                if (W % 2 == 0 && hc > 1) energy -= double(eq[hc - 1]);
            }
        }
        // Adaptive balance of tau and sigma (product constant), Goldstein et al.: the primal
        // residual is K^T y (G = 0), the dual residual comes from the previous dual step.
        if (adapt) {
            const double pres = std::sqrt(energy * inv_n);
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
        fft.inverse_unscaled_destroy(spec2, dx);  // M^-1 K^T y
        fft.inverse_unscaled_destroy(spec3, aw);  // beta H M^-1 K^T y (before the crop)

        const T tt = static_cast<T>(tau), st = static_cast<T>(sigma), gt = static_cast<T>(gamma);
        const T inv_s = T(1) / st;
        // The dual residual feeds the step balance only while it adapts; the change only a
        // tolerance > 0; alpha never grows, so a skipped sum is never needed later.
        const bool want_dres = alpha > kAlphaStop;
        const bool want_change = o.tolerance > 0.0;
        double xn2 = 0.0, step2 = 0.0, d2 = 0.0, neg2 = 0.0, tv = 0.0;
        const bool want_tv = o.record_history;
        // Primal step of row rr: x <- x - tau dx, dx <- the step d; the non-negativity block.
        auto x_row = [&](int rr) {
            T* __restrict xq = xp;
            T* __restrict dq = dp;
            const Eigen::Index o0 = Eigen::Index(rr) * W;
            T* __restrict aq = row_a.data();
            T* __restrict bq = row_b.data();
            for (int c = 0; c < W; ++c) {
                const Eigen::Index i = o0 + c;
                const T d = tt * dq[i];
                const T xn = xq[i] - d;
                xq[i] = xn;
                dq[i] = d;
                aq[c] = xn * xn;
                bq[c] = d * d;
            }
            if (want_change) {
                xn2 += row_sum(row_a, W);
                step2 += row_sum(row_b, W);
            }
            if (!nn) return;
            T* __restrict wq = ywp;
            for (int c = 0; c < W; ++c) {
                const Eigen::Index i = o0 + c;
                const T xn = xq[i], d = dq[i], ywo = wq[i];
                const T ywn = std::min(T(0), ywo + st * gt * (xn - d));  // at xbar = x_new - d
                const T e = (ywo - ywn) * inv_s - gt * d;
                aq[c] = e * e;
                wq[i] = ywn;
                const T neg = std::min(xn, T(0));
                bq[c] = neg * neg;
            }
            if (want_dres) d2 += row_sum(row_a, W);
            neg2 += row_sum(row_b, W);
        };
        // Dual step of the gradient block, row rr (rows rr and rr + 1 of x final): y1 <- the
        // projection on the unit ball of y1 + sigma grad xbar, xbar = x_new - d. The last column
        // (periodic neighbour) apart, so the row loop has no wrap-around index.
        auto dual_row = [&](int rr) {
            const T* __restrict xq = xp;
            const T* __restrict dq = dp;
            T* __restrict yrq = yrp;
            T* __restrict ycq = ycp;
            const Eigen::Index o0 = Eigen::Index(rr) * W;
            const Eigen::Index od = Eigen::Index(rr + 1 < R ? rr + 1 : 0) * W - o0;
            const T* xr = xq + o0;
            const T* dr = dq + o0;
            if (want_tv) {
                dual_row_points<T, true>(xr, xr + od, dr, dr + od, yrq + o0, ycq + o0, row_e.data(),
                                         row_tv.data(), W, st, inv_s);
            } else {
                dual_row_points<T, false>(xr, xr + od, dr, dr + od, yrq + o0, ycq + o0,
                                          row_e.data(), row_tv.data(), W, st, inv_s);
            }
            if (want_dres) d2 += row_sum(row_e, W);
            if (want_tv) tv += row_sum(row_tv, W);
        };
        // K^T y of row rr (rows rr - 1 and rr of y1 final): -div y1 + gamma y_w.
        auto kty_row = [&](int rr) {
            const T* __restrict yrq = yrp;
            const T* __restrict ycq = ycp;
            T* __restrict kq = kp;
            const Eigen::Index o0 = Eigen::Index(rr) * W;
            const Eigen::Index up = Eigen::Index(rr > 0 ? rr - 1 : R - 1) * W - o0;
            kq[o0] = yrq[o0 + up] - yrq[o0] + ycq[o0 + W - 1] - ycq[o0];
            for (Eigen::Index i = o0 + 1; i < o0 + W; ++i)
                kq[i] = yrq[i + up] - yrq[i] + ycq[i - 1] - ycq[i];
            if (nn) {
                for (Eigen::Index i = o0; i < o0 + W; ++i) kq[i] += gt * ywp[i];
            }
        };
        for (int rr = 0; rr < R; ++rr) {
            x_row(rr);
            if (rr >= 1) dual_row(rr - 1);
            if (rr >= 2) kty_row(rr - 1);
        }
        dual_row(R - 1);
        if (R > 1) kty_row(R - 1);
        kty_row(0);

        // The data block in two passes over the capture window: beta A x_new and the norms of
        // v / sigma - beta p (v = y_q + sigma beta A xbar) and of the residual; then y_q <- v -
        // sigma proj_B(v / sigma) = (1 - min(1, radius / |z|)) (v - sigma beta p).
        double zn2 = 0.0, res2 = 0.0;
        for (int i = 0; i < pr; ++i) {
            const T* __restrict wrow = aw.data() + Eigen::Index(cr + i) * W + cc;
            T* __restrict ba = bax.data() + Eigen::Index(i) * pc;
            const T* __restrict b = bp.data() + Eigen::Index(i) * pc;
            const T* __restrict q = yq.data() + Eigen::Index(i) * pc;
            T* __restrict aq = row_a.data();
            T* __restrict bq = row_b.data();
            for (int c = 0; c < pc; ++c) {
                const T t = tt * wrow[c];
                const T ban = ba[c] - t;
                ba[c] = ban;
                const T z = q[c] * inv_s + (ban - t) - b[c];
                const T e = ban - b[c];
                aq[c] = z * z;
                bq[c] = e * e;
            }
            zn2 += row_sum(row_a, pc);
            res2 += row_sum(row_b, pc);
        }
        const double zn = std::sqrt(zn2);
        const T keep = static_cast<T>(zn > radius ? 1.0 - radius / zn : 0.0);
        double q2 = 0.0;
        for (int i = 0; i < pr; ++i) {
            const T* __restrict wrow = aw.data() + Eigen::Index(cr + i) * W + cc;
            const T* __restrict ba = bax.data() + Eigen::Index(i) * pc;
            const T* __restrict b = bp.data() + Eigen::Index(i) * pc;
            T* __restrict q = yq.data() + Eigen::Index(i) * pc;
            T* __restrict aq = row_a.data();
            for (int c = 0; c < pc; ++c) {
                const T t = tt * wrow[c];
                const T v = q[c] + st * (ba[c] - t);
                const T qn = keep * (v - st * b[c]);
                const T e = (q[c] - qn) * inv_s - t;
                aq[c] = e * e;
                q[c] = qn;
            }
            if (want_dres) q2 += row_sum(row_a, pc);
        }
        dres_prev = std::sqrt(d2 + q2);

        // tolerance 0 never stops on the change (its sums are skipped), as a nonzero step never
        // met change <= 0.
        const double change = !want_change   ? std::numeric_limits<double>::infinity()
                              : step2 == 0.0 ? 0.0
                                             : std::sqrt(step2 / xn2);
        const double res = std::sqrt(res2) / beta;
        const double viol = std::max(res - eps, 0.0) + (nn ? std::sqrt(neg2) : 0.0);
        r.iterations = k;
        if (o.record_history) {
            IterationRecord rec;
            rec.iteration = k;
            rec.objective = tv;
            rec.residual = relative_residual(res);
            rec.seconds = clock.seconds();
            r.history.push_back(rec);
        }
        // k >= 2: the first primal step starts from y = 0 and does not move x.
        const bool converged =
            k >= 2 && change <= o.tolerance && viol <= o.tolerance * std::max(eps, p_norm);
        if (iteration_ends(converged, o, r)) break;
    }
    x_io = x.template cast<double>();
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
    const bool nn = o.nonnegative;
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
    ComplexPlane spec, scratch;
    Plane work;
    auto apply_a = [&](const Plane& x, Plane& out) {  // out = A x
        fft.forward(x, spec);
        spec *= H;
        fft.inverse(spec, work, scratch);
        out = work.block(g.crop_row, g.crop_col, g.capture_rows, g.capture_cols);
    };

    const FeasiblePoint start =
        eps > 0.0 ? smooth_feasible_point(op, capture, eps) : FeasiblePoint{};
    Plane x = warm_start  ? *warm_start
              : eps > 0.0 ? start.x
                          : Plane::Zero(g.work_rows, g.work_cols);
    if (o.single_precision) {
        pdhg<float>(op, capture, o, p_norm, x, r, clock);
    } else {
        pdhg<double>(op, capture, o, p_norm, x, r, clock);
    }
    Plane ax;
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
