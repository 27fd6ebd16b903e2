#include "decode/solvers/tv_l2.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/gradient.hpp"
#include "decode/solvers/precision.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#define PM_TV_AVX2 1
#define PM_TV_INLINE inline __attribute__((always_inline))
#else
#define PM_TV_AVX2 0
#define PM_TV_INLINE inline
#endif

namespace pinmask {

bool tv_l2_avx2_available() {
#if PM_TV_AVX2
    static const bool has = [] {
        __builtin_cpu_init();  // may run before the library's own CPU-model constructor
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return has;
#else
    return false;
#endif
}

namespace {
// -1 until first use (then the CPU's answer), or what set_tv_l2_avx2 chose.
std::atomic<int> tv_l2_avx2_mode{-1};
bool tv_l2_avx2_enabled() {
    int m = tv_l2_avx2_mode.load(std::memory_order_relaxed);
    if (m < 0) {
        m = tv_l2_avx2_available() ? 1 : 0;
        tv_l2_avx2_mode.store(m, std::memory_order_relaxed);
    }
    return m == 1;
}
}  // namespace

void set_tv_l2_avx2(bool enabled) {
    tv_l2_avx2_mode.store(enabled && tv_l2_avx2_available() ? 1 : 0, std::memory_order_relaxed);
}

namespace {

// Residual balancing (Boyd et al. 2011, sec. 3.4.1): adapt when one residual is kMu times the
// other, by the factor kTau, every kAdaptEvery iterations up to kAdaptUntil (then rho stays
// fixed, so the usual ADMM convergence proof applies to the tail). Tuned on the paper problem of
// bench/decode_bench (lambda 1e-4, 1e-3, 1e-2): every 3 with mu 2 reached 0.2 dB of converged
// in 6, 18, 34 iterations, every 10 with mu 10 (the earlier rule) in 9, 34, 61+; faster
// adaptation (every 1 or 2) oscillates.
constexpr double kMu = 2.0;
constexpr double kTau = 2.0;
constexpr int kAdaptEvery = 3;
constexpr int kAdaptUntil = 100;
// The linear model adapts two penalties (the TV split's rho and the crop split's rho_s), and the
// cyclic rule oscillates there: on bench/linear_convergence's simulated full-frame captures (a
// quarter size, x >= 0) the iterations to within 0.2 dB of converged were 83 / 385 / 401+ (paper
// sensor, refocused at 2 m, DiffuserCam PSF) with every 3, mu 2, tau 2, and 36 / 40 / 49 with
// every 5, mu 3, tau 1.5 (every 4-5, mu 2-5 at tau 1.5 all within 34-49; every 3 or tau 2 at
// every 4 or 6 fell back to hundreds on one case). At half size: 353 / 401+ / 401+ against
// 50 / 51 / 138. Every 5 then proved too eager on the full-size problems of scripts/bench-peers
// (the residuals are in different units, so balancing raises both penalties at every
// adaptation until kAdaptUntil: 1.5^20 = 3300x mean |H|^2 on the DiffuserCam PSF at 300 x 400,
// where the ADMM then crawls: 17.11 dB after 400 iterations, 17.73 after 1600). Every 10 stops
// at 58x there and reaches 19.57 dB after 400 (converged: 19.55 after 800); on the pinhole
// array's exact PSF over 240 x 360 18.24 against 17.24 dB after 400, on the lensless array
// 18.14 against 16.54 after 200 (lambda 1e-4, 1e-4, 3e-4 x the capture's peak). It doubles the
// count on the quarter-size problems (36 / 40 to 68 / 78) and converges to the same PSNR.
// Balancing relative residuals (Wohlberg 2017) settled at 86x / 7.6x but reached 19.31 dB after
// 400 on the DiffuserCam problem, so the simpler rule stays. tests/bench/test_linear_convergence
// holds the counts.
constexpr double kMuLinear = 3.0;
constexpr double kTauLinear = 1.5;
constexpr int kAdaptEveryLinear = 10;
// Over-relaxation (Eckstein and Bertsekas 1992; Boyd et al. sec. 3.4.3): alpha in (0, 2); 1.8
// cut the iterations to 0.2 dB by ~45% against alpha = 1 on the paper problem. The cyclic model
// without the nonnegative split takes 1.95: on the paper problem (lambda 1e-4, 1e-3, 1e-2) 6, 17,
// 32 iterations to 0.2 dB against 6, 18, 34 at 1.8; over seeds 1-3, sizes 64, 128, 256 and the
// three lambdas equal or fewer in 26 of 27 cases (seed 2, 64 x 64, lambda 1e-3: 14 against 24),
// one more in one (9 against 8); with nonnegative (lambda 1e-4: 20 against 10)
// and on the linear model (DiffuserCam hand, lambda 1e-4, the objective after 30 and 100
// iterations 24 % and 6 % higher) 1.95 is slower, so those keep 1.8.
constexpr double kRelaxation = 1.8;
constexpr double kRelaxationCyclic = 1.95;

// Multiplies rho by kTau, divides it, or leaves it; returns the factor applied.
double balance(double primal, double dual, double& rho, double mu, double tau) {
    if (primal > mu * dual) {
        rho *= tau;
        return tau;
    }
    if (dual > mu * primal) {
        rho /= tau;
        return 1.0 / tau;
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

// Sums the z-step gathers when asked (adaptation, records): residuals and TV, in double.
struct ZSums {
    double prim2 = 0.0, dual2 = 0.0, tv = 0.0;
    double dx2 = 0.0, x2 = 0.0;  // ||x - x_old||^2 and ||x||^2, when x_old is given
};

// The ADMM state of the z = grad x split, raw arrays of R x C (row-major).
template <class T>
struct ZState {
    T* zr;
    T* zc;
    T* ur;
    T* uc;
    double* ep;  // scratch rows of C for the residual sums (the vectorised stats path)
    double* ed;
    T* sr;  // scratch rows of C for the old z (the same path)
    T* sc;
};

// Sum of n doubles in four interleaved partial sums (a fixed order: deterministic), so the adds
// do not wait on one another.
inline double sum4(const double* __restrict a, int n) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    int i = 0;
    for (; i + 3 < n; i += 4) {
        s0 += a[i];
        s1 += a[i + 1];
        s2 += a[i + 2];
        s3 += a[i + 3];
    }
    for (; i < n; ++i) s0 += a[i];
    return (s0 + s1) + (s2 + s3);
}

// One pixel of the z-step: isotropic shrinkage by thr of the over-relaxed gradient
// alpha g + (1 - alpha) z + u; z, u updated in place. Branch-free, on restrict pointers, in a TU
// built with -fno-math-errno (decode/CMakeLists.txt), so the compiler vectorises the row loop:
// f = max(0, 1 - thr / max(|a|, tiny)) is 1 - thr / |a| when |a| > thr, else 0.
template <class T, bool kStats>
PM_TV_INLINE void z_point(T gr, T gc, Eigen::Index i, T* __restrict zr, T* __restrict zc,
                          T* __restrict ur, T* __restrict uc, T alpha, T thr, bool want_tv,
                          ZSums& sums) {
    const T zr0 = zr[i], zc0 = zc[i];
    const T ar = alpha * gr + (T(1) - alpha) * zr0 + ur[i];
    const T ac = alpha * gc + (T(1) - alpha) * zc0 + uc[i];
    const T mag = std::sqrt(ar * ar + ac * ac);
    const T f = std::max(T(0), T(1) - thr / std::max(mag, std::numeric_limits<T>::min()));
    const T zr1 = f * ar, zc1 = f * ac;
    zr[i] = zr1;
    zc[i] = zc1;
    ur[i] = ar - zr1;
    uc[i] = ac - zc1;
    if (kStats) {
        const double pr = double(gr) - zr1, pc = double(gc) - zc1;
        const double dr = double(zr1) - zr0, dc = double(zc1) - zc0;
        sums.prim2 += pr * pr + pc * pc;
        sums.dual2 += dr * dr + dc * dc;
        if (want_tv) sums.tv += std::sqrt(double(gr) * gr + double(gc) * gc);
    }
}

// z-step of row r (periodic forward differences of x: the row below, the pixel to the right).
template <class T, bool kStats>
PM_TV_INLINE void z_row(const T* __restrict x, int R, int C, int r, const ZState<T>& s, T alpha,
                        T thr, bool want_tv, ZSums& sums) {
    const T* __restrict xr = x + Eigen::Index(r) * C;
    const T* __restrict xd = x + Eigen::Index(r + 1 < R ? r + 1 : 0) * C;
    T* __restrict zr = s.zr + Eigen::Index(r) * C;
    T* __restrict zc = s.zc + Eigen::Index(r) * C;
    T* __restrict ur = s.ur + Eigen::Index(r) * C;
    T* __restrict uc = s.uc + Eigen::Index(r) * C;
    {
        // Adaptation (kStats): z and the old z kept in scratch rows, then the same vectorised
        // loop as below, then the squared residuals per pixel, summed by sum4.
        T* __restrict z0r = kStats ? s.sr : nullptr;
        T* __restrict z0c = kStats ? s.sc : nullptr;
        if (kStats) {
            for (int c = 0; c + 1 < C; ++c) {
                z0r[c] = zr[c];
                z0c[c] = zc[c];
            }
        }
        // z_point's arithmetic written out: this form is the one GCC 12 vectorises
        const T beta = T(1) - alpha, tiny = std::numeric_limits<T>::min();
        for (int c = 0; c + 1 < C; ++c) {
            const T ar = alpha * (xd[c] - xr[c]) + beta * zr[c] + ur[c];
            const T ac = alpha * (xr[c + 1] - xr[c]) + beta * zc[c] + uc[c];
            const T f = std::max(T(0), T(1) - thr / std::max(std::sqrt(ar * ar + ac * ac), tiny));
            zr[c] = f * ar;
            zc[c] = f * ac;
            ur[c] = ar - f * ar;
            uc[c] = ac - f * ac;
        }
        if (kStats) {
            double* __restrict ep = s.ep;
            double* __restrict ed = s.ed;
            for (int c = 0; c + 1 < C; ++c) {
                const double pr = double(xd[c] - xr[c]) - double(zr[c]);
                const double pc = double(xr[c + 1] - xr[c]) - double(zc[c]);
                const double dr = double(zr[c]) - double(z0r[c]);
                const double dc = double(zc[c]) - double(z0c[c]);
                ep[c] = pr * pr + pc * pc;
                ed[c] = dr * dr + dc * dc;
            }
            sums.prim2 += sum4(ep, C - 1);
            sums.dual2 += sum4(ed, C - 1);
            if (want_tv) {  // records: |grad x| per pixel, into the scratch row just summed
                for (int c = 0; c + 1 < C; ++c) {
                    const double gr = double(xd[c] - xr[c]), gc = double(xr[c + 1] - xr[c]);
                    ep[c] = std::sqrt(gr * gr + gc * gc);
                }
                sums.tv += sum4(ep, C - 1);
            }
        }
    }
    const int c = C - 1;
    z_point<T, kStats>(xd[c] - xr[c], xr[0] - xr[c], c, zr, zc, ur, uc, alpha, thr, want_tv, sums);
}

// x-step right-hand side of row r: rho grad^T (z - u) [+ rho (w - v)], where grad^T d = -div d
// = -(d_r(i) - d_r(i - row) + d_c(i) - d_c(i - 1)) (periodic). Reads rows r and r - 1 of z, u.
template <class T>
PM_TV_INLINE void rhs_row(int R, int C, int r, const ZState<T>& s, const T* w, const T* v, T rho,
                          T* t) {
    const Eigen::Index o = Eigen::Index(r) * C;
    const Eigen::Index ou = Eigen::Index(r > 0 ? r - 1 : R - 1) * C;
    const T *zr = s.zr, *zc = s.zc, *ur = s.ur, *uc = s.uc;
    {
        const Eigen::Index i = o, left = o + C - 1;
        t[i] =
            rho * ((zr[ou] - ur[ou]) - (zr[i] - ur[i]) + (zc[left] - uc[left]) - (zc[i] - uc[i]));
    }
    for (int c = 1; c < C; ++c) {
        const Eigen::Index i = o + c, up = ou + c;
        t[i] =
            rho * ((zr[up] - ur[up]) - (zr[i] - ur[i]) + (zc[i - 1] - uc[i - 1]) - (zc[i] - uc[i]));
    }
    if (w != nullptr) {
        for (int c = 0; c < C; ++c) t[o + c] += rho * (w[o + c] - v[o + c]);
    }
}

// w-step of row r: projection on x >= 0 of the over-relaxed alpha x + (1 - alpha) w + v.
// Adds ||x - w||^2 and ||w - w_old||^2 to the sums when asked.
template <class T, bool kStats>
PM_TV_INLINE void w_row(const T* x, int C, int r, T* w, T* v, T alpha, ZSums& sums) {
    const Eigen::Index o = Eigen::Index(r) * C;
    for (Eigen::Index i = o; i < o + C; ++i) {
        const T xh = alpha * x[i] + (T(1) - alpha) * w[i];
        const T w_new = std::max(T(0), xh + v[i]);
        if (kStats) {
            const double dw = double(w_new) - w[i], pw = double(x[i]) - w_new;
            sums.dual2 += dw * dw;
            sums.prim2 += pw * pw;
        }
        v[i] = v[i] + xh - w_new;
        w[i] = w_new;
    }
}

// The fused pass after the x-step: per row the z-step, the w-step, and the right-hand side of
// the next x-step for the row above (whose z, u, w, v are final); row 0's at the end.
// The squared change and the squared value of one row of x, per pixel, in double.
template <class T>
PM_TV_INLINE void change_row(const T* __restrict x, const T* __restrict x_old, int C,
                             double* __restrict ed, double* __restrict ex) {
    for (int c = 0; c < C; ++c) {
        const double d = double(x[c]) - double(x_old[c]);
        ed[c] = d * d;
        ex[c] = double(x[c]) * double(x[c]);
    }
}

// x_old (optional): the previous x, whose relative change the pass sums too (the row of x is in
// cache from the z-step: one extra read instead of a pass over both planes).
template <class T, bool kStats>
PM_TV_INLINE ZSums fused_pass_body(const T* x, const T* x_old, int R, int C, const ZState<T>& s,
                                   T* w, T* v, T alpha, T thr, T rho, bool want_tv, T* t) {
    ZSums sums;
    for (int r = 0; r < R; ++r) {
        z_row<T, kStats>(x, R, C, r, s, alpha, thr, want_tv, sums);
        if (w != nullptr) w_row<T, kStats>(x, C, r, w, v, alpha, sums);
        if (r > 0) rhs_row(R, C, r, s, w, v, rho, t);
        if (x_old != nullptr) {
            const Eigen::Index o = Eigen::Index(r) * C;
            change_row(x + o, x_old + o, C, s.ep, s.ed);
            sums.dx2 += sum4(s.ep, C);
            sums.x2 += sum4(s.ed, C);
        }
    }
    rhs_row(R, C, 0, s, w, v, rho, t);
    return sums;
}

// The fused pass, compiled twice: for the x86-64 baseline (SSE2) and, when the CPU has it, for
// AVX2 (twice the vector width for the shrinkage's sqrt and division, which dominate the pass).
// Both do the same IEEE operations on every pixel in the same order (no FMA: AVX2 does not
// imply it, and this file is built with -ffp-contract=off), and the sums use fixed partial-sum
// orders, so the two give identical bits (tests/decode/test_tv_l2.cpp checks it).
#if PM_TV_AVX2
template <class T, bool kStats>
__attribute__((target("avx2"))) ZSums fused_pass_avx2(const T* x, const T* x_old, int R, int C,
                                                      const ZState<T>& s, T* w, T* v, T alpha,
                                                      T thr, T rho, bool want_tv, T* t) {
    return fused_pass_body<T, kStats>(x, x_old, R, C, s, w, v, alpha, thr, rho, want_tv, t);
}
#endif

template <class T, bool kStats>
ZSums fused_pass(const T* x, const T* x_old, int R, int C, const ZState<T>& s, T* w, T* v, T alpha,
                 T thr, T rho, bool want_tv, T* t) {
#if PM_TV_AVX2
    if (tv_l2_avx2_enabled()) {
        return fused_pass_avx2<T, kStats>(x, x_old, R, C, s, w, v, alpha, thr, rho, want_tv, t);
    }
#endif
    return fused_pass_body<T, kStats>(x, x_old, R, C, s, w, v, alpha, thr, rho, want_tv, t);
}

// The cyclic x-step without records, X = (F[rhs] + conj(H) P) / denominator, in place; built
// for the baseline and for AVX2 like the fused pass (a complex add and a real scaling per
// frequency: the same bits either way).
template <class T>
PM_TV_INLINE void spectral_solve_body(std::complex<T>* __restrict sp,
                                      const std::complex<T>* __restrict htp, const T* __restrict id,
                                      Eigen::Index nh) {
    // On the interleaved real and imaginary parts (std::complex's array access): std::complex's
    // own operators do not vectorise here; (a + b) r is the same per part.
    T* __restrict s2 = reinterpret_cast<T*>(sp);
    const T* __restrict h2 = reinterpret_cast<const T*>(htp);
    for (Eigen::Index i = 0; i < nh; ++i) {
        s2[2 * i] = (s2[2 * i] + h2[2 * i]) * id[i];
        s2[2 * i + 1] = (s2[2 * i + 1] + h2[2 * i + 1]) * id[i];
    }
}
#if PM_TV_AVX2
template <class T>
__attribute__((target("avx2"))) void spectral_solve_avx2(std::complex<T>* sp,
                                                         const std::complex<T>* htp, const T* id,
                                                         Eigen::Index nh) {
    spectral_solve_body<T>(sp, htp, id, nh);
}
#endif
template <class T>
void spectral_solve(std::complex<T>* sp, const std::complex<T>* htp, const T* id, Eigen::Index nh) {
#if PM_TV_AVX2
    if (tv_l2_avx2_enabled()) return spectral_solve_avx2<T>(sp, htp, id, nh);
#endif
    spectral_solve_body<T>(sp, htp, id, nh);
}

// The linear x-step, in place: X = (F[rhs] + rho_s conj(H) Q) / denominator into sp and H X into
// sq (Q = F[s - eta] on entry). Complex products written out on the interleaved parts:
// std::complex's operator* calls __mulsc3 (the C99 Inf/NaN rules) and keeps the loop scalar.
template <class T>
PM_TV_INLINE void linear_spectral_solve_body(std::complex<T>* __restrict sp,
                                             std::complex<T>* __restrict sq,
                                             const std::complex<T>* __restrict h,
                                             const T* __restrict id, T rho_s, Eigen::Index nh) {
    T* __restrict a = reinterpret_cast<T*>(sp);
    T* __restrict q = reinterpret_cast<T*>(sq);
    const T* __restrict hh = reinterpret_cast<const T*>(h);
    for (Eigen::Index i = 0; i < nh; ++i) {
        const T hr = hh[2 * i], hi = hh[2 * i + 1];
        const T qr = q[2 * i], qi = q[2 * i + 1];
        const T xr = (a[2 * i] + rho_s * (hr * qr + hi * qi)) * id[i];
        const T xi = (a[2 * i + 1] + rho_s * (hr * qi - hi * qr)) * id[i];
        a[2 * i] = xr;
        a[2 * i + 1] = xi;
        q[2 * i] = hr * xr - hi * xi;
        q[2 * i + 1] = hr * xi + hi * xr;
    }
}
#if PM_TV_AVX2
template <class T>
__attribute__((target("avx2"))) void linear_spectral_solve_avx2(std::complex<T>* sp,
                                                                std::complex<T>* sq,
                                                                const std::complex<T>* h,
                                                                const T* id, T rho_s,
                                                                Eigen::Index nh) {
    linear_spectral_solve_body<T>(sp, sq, h, id, rho_s, nh);
}
#endif
template <class T>
void linear_spectral_solve(std::complex<T>* sp, std::complex<T>* sq, const std::complex<T>* h,
                           const T* id, T rho_s, Eigen::Index nh) {
#if PM_TV_AVX2
    if (tv_l2_avx2_enabled()) return linear_spectral_solve_avx2<T>(sp, sq, h, id, rho_s, nh);
#endif
    linear_spectral_solve_body<T>(sp, sq, h, id, rho_s, nh);
}

// The crop split s = H x of the linear model, held as q = s - eta on the working grid (the next
// x-step's transform input) and eta on the capture window only: outside the window C^T C = 0, so
// the s-step there is s = the over-relaxed H x + eta and leaves eta = 0 (it starts at 0), q = s.
// Inside, s = (p + rho_s (hxh + eta)) / (1 + rho_s), eta += hxh - s, with hxh = alpha H x +
// (1 - alpha) s_old. Sums of the residuals ||H x - s||^2 and ||s - s_old||^2 when kStats.
struct SSums {
    double prim2 = 0.0, dual2 = 0.0;
};
struct CropWindow {
    int R, C;            // working grid
    int r0, c0, pr, pc;  // capture window
};
// Outside the window: q = alpha hx + (1 - alpha) q over n pixels (and the residual terms).
template <class T, bool kStats>
PM_TV_INLINE void s_outside(const T* __restrict hx, T* __restrict q, double* __restrict ea,
                            double* __restrict eb, int n, T alpha, T beta) {
    for (int c = 0; c < n; ++c) {
        const T qo = q[c], h = hx[c];
        const T qn = alpha * h + beta * qo;
        q[c] = qn;
        if (kStats) {
            ea[c] = double(h - qn) * double(h - qn);
            eb[c] = double(qn - qo) * double(qn - qo);
        }
    }
}
template <class T, bool kStats>
PM_TV_INLINE SSums s_step_body(const T* __restrict hx, T* __restrict q, T* __restrict eta,
                               const T* __restrict p, const CropWindow& wnd, T alpha, T rho_s,
                               double* __restrict ea, double* __restrict eb) {
    SSums sums;
    const T beta = T(1) - alpha, inv = T(1) / (T(1) + rho_s);
    for (int r = 0; r < wnd.R; ++r) {
        const Eigen::Index o = Eigen::Index(r) * wnd.C;
        if (r < wnd.r0 || r >= wnd.r0 + wnd.pr) {
            s_outside<T, kStats>(hx + o, q + o, ea, eb, wnd.C, alpha, beta);
        } else {
            s_outside<T, kStats>(hx + o, q + o, ea, eb, wnd.c0, alpha, beta);
            const int c1 = wnd.c0 + wnd.pc;
            s_outside<T, kStats>(hx + o + c1, q + o + c1, ea + c1, eb + c1, wnd.C - c1, alpha,
                                 beta);
            const Eigen::Index ow = Eigen::Index(r - wnd.r0) * wnd.pc;
            const Eigen::Index og = o + wnd.c0;
            T* __restrict qr = q + og;
            const T* __restrict hr = hx + og;
            T* __restrict er = eta + ow;
            const T* __restrict pw = p + ow;
            double* __restrict ear = ea + wnd.c0;
            double* __restrict ebr = eb + wnd.c0;
            for (int c = 0; c < wnd.pc; ++c) {
                const T e = er[c], so = qr[c] + e, h = hr[c];
                const T hxh = alpha * h + beta * so;
                const T sn = (pw[c] + rho_s * (hxh + e)) * inv;
                const T en = e + hxh - sn;
                er[c] = en;
                qr[c] = sn - en;
                if (kStats) {
                    ear[c] = double(h - sn) * double(h - sn);
                    ebr[c] = double(sn - so) * double(sn - so);
                }
            }
        }
        if (kStats) {
            sums.prim2 += sum4(ea, wnd.C);
            sums.dual2 += sum4(eb, wnd.C);
        }
    }
    return sums;
}
#if PM_TV_AVX2
template <class T, bool kStats>
__attribute__((target("avx2"))) SSums s_step_avx2(const T* hx, T* q, T* eta, const T* p,
                                                  const CropWindow& wnd, T alpha, T rho_s,
                                                  double* ea, double* eb) {
    return s_step_body<T, kStats>(hx, q, eta, p, wnd, alpha, rho_s, ea, eb);
}
#endif
template <class T, bool kStats>
SSums s_step(const T* hx, T* q, T* eta, const T* p, const CropWindow& wnd, T alpha, T rho_s,
             double* ea, double* eb) {
#if PM_TV_AVX2
    if (tv_l2_avx2_enabled())
        return s_step_avx2<T, kStats>(hx, q, eta, p, wnd, alpha, rho_s, ea, eb);
#endif
    return s_step_body<T, kStats>(hx, q, eta, p, wnd, alpha, rho_s, ea, eb);
}

// The ADMM iteration in precision T on the normalised problem (capture / scale, lambda / scale).
// Fused pointwise loops over raw arrays; every buffer is allocated before the loop.
template <class T>
DecodeResult run_admm(const ConvolutionOperator& op, const Plane& capture_d, const TvL2Options& o,
                      const Plane* warm_start, double scale, const SolverClock& clock) {
    using P = typename PrecisionTypes<T>::Plane;
    using C = typename PrecisionTypes<T>::Spectrum;
    using Cx = std::complex<T>;
    const ConvGeometry& g = op.geometry();
    const int R = g.work_rows, Cc = g.work_cols;
    const Eigen::Index n = Eigen::Index(R) * Cc;
    const int hc = Cc / 2 + 1;
    const Eigen::Index nh = Eigen::Index(R) * hc;
    const bool linear = g.model == ConvModel::kLinear;
    const bool nn = o.nonnegative;
    const typename PrecisionTypes<T>::Fft fft(R, Cc);
    const double inv_n = 1.0 / static_cast<double>(n);
    const double lambda = o.lambda / scale;
    const double alpha = linear || nn ? kRelaxation : kRelaxationCyclic;

    const C H = op.otf().cast<Cx>();
    const Plane h2d = op.otf().abs2();
    const Plane gram = gradient_gram_symbol(R, Cc);
    const P p_w = (capture_d / scale).cast<T>();  // the capture (window) in T
    const CropWindow wnd{R, Cc, g.crop_row, g.crop_col, g.capture_rows, g.capture_cols};
    // kAuto: the quadratic start for the cyclic model, 0 for the linear model (on the quarter-size
    // paper sensor the quadratic start read 16.2 against 14.6 dB after one iteration but 17.8
    // against 18.1 dB after 30 and 19.3 against 19.4 after 300).
    const bool init =
        !warm_start && (o.start == TvStart::kQuadratic || (o.start == TvStart::kAuto && !linear));
    C htp;  // conj(H) F[C^T p] (cyclic; linear with the quadratic start)
    C spec, spec2(R, hc);
    if (!linear) {
        fft.forward(p_w, spec);
        htp = H.conjugate() * spec;
    } else if (init) {
        fft.forward(pad_to_work(g, capture_d / scale).template cast<T>().eval(), spec);
        htp = H.conjugate() * spec;
    }

    const double h2_mean = std::max(h2d.mean(), 1e-12);
    // The penalty from the problem: the mean of |H|^2 puts rho |D|^2 on the scale of the data
    // term across the spectrum (on the paper problem 1x beat 0.3x..3x; lambda-proportional
    // choices were 2-3x slower); residual balancing adapts it from there.
    double rho = o.rho > 0.0 ? o.rho : h2_mean;
    // The crop split's penalty: mean |H|^2 / |H(0)|^2, which is rho for a PSF that sums to 1.
    // On simulated full-frame captures (the paper sensor at 6 m and refocused at 2 m, a quarter
    // size, lambda 1e-3) rho_s = 1 (the data term's own weight) left the PSNR at 3 dB after 30
    // iterations and under 5 dB after 300, against 18 and 19.6 dB at rho_s ~ mean |H|^2
    // (bench/linear_convergence). The s-step weighs rho_s against the data term's 1 in capture
    // units, where H x does not change when the PSF is scaled by c (x scales by 1 / c): rho_s
    // must not change either, so it is divided by |H(0)|^2 = (sum of the PSF)^2, which scales
    // like mean |H|^2 (an L2-normalised PSF took hundreds more iterations to the same PSNR).
    const double h0 = std::norm(op.otf()(0, 0));
    double rho_s = o.rho_crop > 0.0 ? o.rho_crop
                   : o.rho > 0.0    ? o.rho
                                    : h2_mean / std::max(h0, 1e-300);
    P inv_denom(R, hc);  // 1 / (N x-step denominator): the 1/N of the inverse FFT folded in
    auto update_denominator = [&] {
        for (Eigen::Index i = 0; i < nh; ++i) {
            const double d =
                (linear ? rho_s : 1.0) * h2d.data()[i] + rho * gram.data()[i] + (nn ? rho : 0.0);
            inv_denom.data()[i] = static_cast<T>(inv_n / d);
        }
    };
    update_denominator();

    P x = warm_start ? P((*warm_start / scale).cast<T>()) : P(P::Zero(R, Cc));
    P zr = P::Zero(R, Cc), zc = P::Zero(R, Cc), ur = P::Zero(R, Cc), uc = P::Zero(R, Cc),
      tmp(R, Cc), x_old(R, Cc);
    P w, v, q, eta, hx;  // q = s - eta on the grid, eta on the capture window (linear)
    std::vector<double> stat_rows(2 * static_cast<std::size_t>(Cc));
    std::vector<T> old_z_rows(2 * static_cast<std::size_t>(Cc));
    const ZState<T> zs{zr.data(),         zc.data(),
                       ur.data(),         uc.data(),
                       stat_rows.data(),  stat_rows.data() + Cc,
                       old_z_rows.data(), old_z_rows.data() + Cc};

    if (init) {  // x0 = the quadratic (gradient-Tikhonov, weight rho) estimate: one inverse FFT
        // (the linear model's on the zero-padded capture: the crop's weight rho_s folded out)
        const T f = static_cast<T>(linear ? rho_s : 1.0);
        for (Eigen::Index i = 0; i < nh; ++i)
            spec.data()[i] = f * htp.data()[i] * inv_denom.data()[i];
        fft.inverse_unscaled_destroy(spec, x);
    }
    // z = shrink(grad x0, lambda / rho), u = grad x0 - z (as after a z-step with alpha = 1 from
    // z = u = 0); with neither a start estimate nor a warm start, z = grad x0 = 0 and u = 0.
    {
        ZSums unused;
        const T thr0 = static_cast<T>(init || warm_start ? lambda / rho : 0.0);
        for (int r = 0; r < R; ++r)
            z_row<T, false>(x.data(), R, Cc, r, zs, T(1), thr0, false, unused);
    }
    if (nn) {
        w = x.max(T(0));
        v = P::Zero(R, Cc);
    }
    auto full_rhs = [&] {
        for (int r = 0; r < R; ++r)
            rhs_row(R, Cc, r, zs, nn ? w.data() : nullptr, nn ? v.data() : nullptr,
                    static_cast<T>(rho), tmp.data());
    };
    full_rhs();
    std::vector<double> s_rows;  // the s-step's residual terms of one row (linear)
    if (linear) {
        hx.resize(R, Cc);
        fft.forward(x, spec);
        for (Eigen::Index i = 0; i < nh; ++i) spec.data()[i] *= H.data()[i] * T(inv_n);
        fft.inverse_unscaled_destroy(spec, hx);
        // s = (C^T p + rho_s H x) / (C^T C 1 + rho_s), eta = 0: q = s.
        q = hx;
        eta = P::Zero(g.capture_rows, g.capture_cols);
        q.block(g.crop_row, g.crop_col, g.capture_rows, g.capture_cols) =
            (p_w + T(rho_s) * hx.block(g.crop_row, g.crop_col, g.capture_rows, g.capture_cols)) /
            T(1 + rho_s);
        s_rows.resize(2 * static_cast<std::size_t>(Cc));
    }
    P ax;  // H x for the records (cyclic)
    DecodeResult r;
    r.converged = false;

    for (int k = 1; k <= o.max_iterations; ++k) {
        // x-step: tmp holds rho grad^T (z - u) [+ rho (w - v)] from the previous fused pass.
        fft.forward(tmp, spec);
        Cx* sp = spec.data();
        Cx* sp2 = spec2.data();
        const T* id = inv_denom.data();
        const Cx* Hd = H.data();
        if (linear) {
            fft.forward(q, spec2);
            linear_spectral_solve<T>(sp, sp2, Hd, id, static_cast<T>(rho_s), nh);
        } else if (o.record_history) {
            const Cx* htpd = htp.data();
            for (Eigen::Index i = 0; i < nh; ++i) {
                const Cx xs = (sp[i] + htpd[i]) * id[i];
                sp[i] = xs;
                sp2[i] = xs * Hd[i];
            }
        } else {
            const Cx* htpd = htp.data();
            spectral_solve<T>(sp, htpd, id, nh);
        }
        x_old.swap(x);
        fft.inverse_unscaled_destroy(spec, x);
        if (linear) {
            fft.inverse_unscaled_destroy(spec2, hx);
        } else if (o.record_history) {
            fft.inverse_unscaled_destroy(spec2, ax);
        }

        // z-step (isotropic shrinkage of the over-relaxed gradient plus u, by lambda / rho),
        // w-step and the next right-hand side in one pass; the residual and TV sums only on the
        // iterations that use them (adaptation, records).
        const bool adapt = k % (linear ? kAdaptEveryLinear : kAdaptEvery) == 0 && k <= kAdaptUntil;
        const bool stats = adapt || o.record_history;

        // s-step (linear model), over-relaxed: hx_hat = alpha H x + (1 - alpha) s; its residual
        // sums only on the adaptation iterations.
        double prim_s = 0.0, dual_s = 0.0;
        if (linear) {
            const T ta = static_cast<T>(alpha), trs = static_cast<T>(rho_s);
            double* ea = s_rows.data();
            double* eb = s_rows.data() + Cc;
            const SSums ss = adapt ? s_step<T, true>(hx.data(), q.data(), eta.data(), p_w.data(),
                                                     wnd, ta, trs, ea, eb)
                                   : s_step<T, false>(hx.data(), q.data(), eta.data(), p_w.data(),
                                                      wnd, ta, trs, ea, eb);
            prim_s = std::sqrt(ss.prim2);
            dual_s = rho_s * std::sqrt(ss.dual2);
        }
        const T ta = static_cast<T>(alpha), tthr = static_cast<T>(lambda / rho);
        T* wd = nn ? w.data() : nullptr;
        T* vd = nn ? v.data() : nullptr;
        // The relative change of x is summed in the same pass when tolerance > 0.
        const T* xo = o.tolerance > 0.0 ? x_old.data() : nullptr;
        const ZSums sums =
            stats ? fused_pass<T, true>(x.data(), xo, R, Cc, zs, wd, vd, ta, tthr,
                                        static_cast<T>(rho), o.record_history, tmp.data())
                  : fused_pass<T, false>(x.data(), xo, R, Cc, zs, wd, vd, ta, tthr,
                                         static_cast<T>(rho), false, tmp.data());

        r.iterations = k;
        // Relative change of x; tolerance 0 stops only when x did not change at all (a
        // comparison that ends at the first difference).
        bool small_change = false;
        if (o.tolerance > 0.0) {
            const double dx2 = sums.dx2, x2 = sums.x2;
            small_change = dx2 == 0.0 || (x2 > 0.0 && std::sqrt(dx2 / x2) <= o.tolerance);
        } else {
            small_change = (x == x_old).all();
        }
        if (o.record_history) {
            // Records follow the ADMM iterate x (for nonnegative, w = max(x + v, 0) tends to x):
            // residual ||C H x - p||, objective 1/2 residual^2 + lambda TV(x), capture units.
            const P& a_est = linear ? hx : ax;
            double res2 = 0.0;
            for (int rr = 0; rr < g.capture_rows; ++rr)
                for (int c = 0; c < g.capture_cols; ++c) {
                    const double d =
                        double(a_est(g.crop_row + rr, g.crop_col + c)) - double(p_w(rr, c));
                    res2 += d * d;
                }
            IterationRecord rec;
            rec.iteration = k;
            rec.residual = std::sqrt(res2) * scale;
            rec.objective = (0.5 * res2 + lambda * sums.tv) * scale * scale;
            rec.seconds = clock.seconds();
            r.history.push_back(rec);
        }
        if (o.observe) o.observe(k, (nn ? w : x).template cast<double>() * scale);
        if (iteration_ends(small_change, o, r)) break;

        if (adapt) {
            const double mu = linear ? kMuLinear : kMu, tau = linear ? kTauLinear : kTau;
            // The gradient split's dual residual in the units of a PSF that sums to 1 (rho /
            // |H(0)|^2): rho follows the PSF's scale squared, the residuals its inverse.
            const double f =
                balance(std::sqrt(sums.prim2), rho / std::max(h0, 1e-300) * std::sqrt(sums.dual2),
                        rho, mu, tau);
            double fs = 1.0;
            if (linear) fs = balance(prim_s, dual_s, rho_s, mu, tau);
            if (f != 1.0) {
                ur /= T(f);
                uc /= T(f);
                if (nn) v /= T(f);
                full_rhs();  // the fused pass built it with the old rho and u
            }
            if (fs != 1.0) {  // eta scales with 1 / rho_s; q = s - eta follows it
                q.block(g.crop_row, g.crop_col, g.capture_rows, g.capture_cols) +=
                    eta * T(1.0 - 1.0 / fs);
                eta /= T(fs);
            }
            if (f != 1.0 || fs != 1.0) update_denominator();
        }
    }
    if (o.max_iterations == 0) {
        r.converged = true;
        if (nn) w = x.max(T(0));
    }
    r.image = (nn ? w : x).template cast<double>() * scale;
    return r;
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
    if (!(o.rho_crop >= 0.0) || !std::isfinite(o.rho_crop)) {
        throw invalid_field("rho_crop", std::to_string(o.rho_crop),
                            "must be finite and >= 0 (0 = automatic)");
    }
    if (warm_start) check_warm_start(*warm_start, g);
    if (!is_all_finite(capture)) {
        throw invalid_field("capture", "non-finite values", "every pixel must be finite");
    }
    // Scale invariance: the problem is solved for p / s with lambda / s and the estimate scaled
    // back (x(c p, c lambda) = c x(p, lambda)), s = max |p| (1 for an all-zero capture), so a
    // capture of any magnitude meets the same numbers inside the solver.
    const double peak = capture.abs().maxCoeff();
    const double scale = peak > 0.0 && std::isfinite(peak) ? peak : 1.0;
    DecodeResult r = o.single_precision
                         ? run_admm<float>(op, capture, o, warm_start, scale, clock)
                         : run_admm<double>(op, capture, o, warm_start, scale, clock);
    // One model application for both (tv_l2_objective's expression, the same bits).
    const double res2 = (op.apply(r.image) - capture).square().sum();
    r.objective = 0.5 * res2 + o.lambda * total_variation(r.image);
    r.residual = std::sqrt(res2);
    r.seconds = clock.seconds();
    return r;
}

}  // namespace pinmask
