#include "decode/calibrate/forward_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "decode/calibrate/grid_read.hpp"
#include "decode/calibrate/profile_table.hpp"
#include "decode/calibrate/spots.hpp"
#include "decode/solvers/convolution.hpp"
#include "design/optics/optics.hpp"

namespace pinmask::calibrate {

namespace {

constexpr int kNonlinear = 6;  // x0, y0, t, px, py, s
enum { kX0 = 0, kY0 = 1, kRot = 2, kPx = 3, kPy = 4, kSide = 5 };
constexpr double kSideStep = 1e-4;  // forward difference of the side scale
constexpr double kMinSideScale = 0.2, kMaxSideScale = 5.0;
constexpr int kRounds = 3;
constexpr double kConvergedChi2 = 1e-2;
constexpr int kSmallSteps = 3;
// A capture is fitted binned when cells are at least 2 kBinnedCellPx pixels wide and the frame
// at least kMinBinnedFramePx on its short side (fit_forward_model).
constexpr double kBinnedCellPx = 8.0;
constexpr int kMinBinnedFramePx = 1024;

struct Params {
    double v[kNonlinear] = {0, 0, 0, 0, 0, 1};
    std::vector<double> g;
    double leak = 0.0, background = 0.0;
};

struct Window {
    int r0 = 0, r1 = -1, c0 = 0, c1 = -1;  // inclusive, clipped to the frame
    std::vector<double> k;                 // kernel values, row-major over the window
    int width() const { return c1 - c0 + 1; }
    bool empty() const { return r1 < r0 || c1 < c0; }
};

struct Problem {
    const Plane& frame;
    const Mask& mask;
    const ForwardFitOptions& o;
    KernelModel family;
    std::vector<Cell> cells;    // open cells of the tiled mask with a window in the frame
    std::vector<Cell> outside;  // open cells whose only light in the frame is their halo
    double cell_px = 1.0;       // design pitch (pixels), for the window sizes
    int rows, cols;
    // The lattice's pivot: (x0, y0) of the parameters is the spot centre of this cell (a cell
    // amid the fitted ones), so rotation and pitches are nearly uncorrelated with the position
    // (about cell (0, 0), often far outside the frame, a small rotation moves every spot far and
    // the fit's valley is long and narrow).
    int ref_row = 0, ref_col = 0;
};

Eigen::Vector2d centre_of(const Problem& pb, const double* v, const Cell& c) {
    const double ct = std::cos(v[kRot]), st = std::sin(v[kRot]);
    const double dc = c.col - pb.ref_col, dr = c.row - pb.ref_row;
    return {v[kX0] + v[kPx] * ct * dc + v[kPy] * st * dr,
            v[kY0] - v[kPx] * st * dc + v[kPy] * ct * dr};
}

double side_m(const Problem& pb, double scale) { return scale * pb.mask.camera.pinhole_m; }

// The window holds core_cells cells, and at least the kernel's central lobes: out to
// v = 2 N + 2 (the Fresnel pattern's geometric half width 2N, then the sinc's second zero;
// fraunhofer N = 0). The halo is held fixed inside a round and placed on whole pixels, so a spot
// whose main lobe is wider than the window (a pinhole small against the cell: the walkthrough's
// 9 px cells with a lobe of 54 px) would be fitted from its halo's fixed point, pulling the
// lattice far off.
double core_half_px(const Problem& pb, double scale) {
    if (pb.family == KernelModel::kBox)
        return profile_support_px(pb.mask.camera, pb.family, side_m(pb, scale), 1.0, 1e9) + 0.5;
    Camera c = pb.mask.camera;
    c.pinhole_m = side_m(pb, scale);
    const double a = c.pinhole_m * c.pixel_pitch_m / (c.wavelength_m * c.sensor_distance_m);
    const double n = pb.family == KernelModel::kFresnel ? fresnel_number_at_u(c) : 0.0;
    return std::max(pb.o.core_cells * pb.cell_px, (2.0 * n + 2.0) / a);
}

// Half width of a spot's core window (pixels): the window is the pixels within this of the
// spot centre's nearest pixel; the halo holds the kernel beyond it.
int core_window_px(const Problem& pb, double scale) {
    return static_cast<int>(std::ceil(core_half_px(pb, scale)));
}

double halo_half_px(const Problem& pb, double scale) {
    if (pb.family == KernelModel::kBox) return 0.0;
    return profile_support_px(pb.mask.camera, pb.family, side_m(pb, scale), pb.o.halo_energy,
                              pb.o.halo_cap_px);
}

// Length of [a - 1/2, a + 1/2] (a pixel along one axis) inside [lo, hi].
double overlap(double a, double lo, double hi) {
    return std::clamp(std::min(a + 0.5, hi) - std::max(a - 0.5, lo), 0.0, 1.0);
}

// The film's area on the sensor: the footprint of the tiled mask without the open cells' clear
// pinholes (each the fitted side's geometric image, centred on its cell), anti-aliased over one
// pixel along each mask axis. The leak L is per pixel of opaque film, so L x cell area / gain is
// the fraction of one pinhole's flux a closed cell passes: the film transmission as the project
// defines it (optimize/simulate/noise_model.hpp). With `opaque_only` false, the whole footprint.
Plane footprint(const Problem& pb, const double* v, bool opaque_only = true) {
    const double ct = std::cos(v[kRot]), st = std::sin(v[kRot]);
    const int n = pb.mask.pattern.n;
    const int ncol = n * pb.mask.pattern.tiles_cols, nrow = n * pb.mask.pattern.tiles_rows;
    std::vector<char> open(static_cast<std::size_t>(n) * n, 0);
    for (const Cell& c : pb.mask.pattern.pinholes) open[c.row * n + c.col] = 1;
    // Half the geometric image of the fitted pinhole (pixels), as the kernel's own scale.
    const double h = 0.5 * std::abs(magnification_at_u(pb.mask.camera)) * side_m(pb, v[kSide]) /
                     pb.mask.camera.pixel_pitch_m;
    Plane f(pb.rows, pb.cols);
    for (int r = 0; r < pb.rows; ++r)
        for (int c = 0; c < pb.cols; ++c) {
            const double dx = c - v[kX0], dy = r - v[kY0];
            // Pixels along the axes from cell (0, 0)'s spot centre ((x0, y0) is the pivot's).
            const double a = ct * dx - st * dy + pb.ref_col * v[kPx];
            const double b = st * dx + ct * dy + pb.ref_row * v[kPy];
            const double fa = overlap(a, -0.5 * v[kPx], (ncol - 0.5) * v[kPx]);
            const double fb = overlap(b, -0.5 * v[kPy], (nrow - 0.5) * v[kPy]);
            double clear = 0.0;
            if (opaque_only && fa * fb > 0) {
                const int kc = static_cast<int>(std::floor(a / v[kPx] + 0.5));
                const int kr = static_cast<int>(std::floor(b / v[kPy] + 0.5));
                for (int i = kr - 1; i <= kr + 1; ++i)
                    for (int j = kc - 1; j <= kc + 1; ++j) {
                        if (i < 0 || j < 0 || i >= nrow || j >= ncol || !open[(i % n) * n + j % n])
                            continue;
                        clear += overlap(a, j * v[kPx] - h, j * v[kPx] + h) *
                                 overlap(b, i * v[kPy] - h, i * v[kPy] + h);
                    }
            }
            f(r, c) = std::max(0.0, fa * fb - std::min(clear, 1.0));
        }
    return f;
}

// The halo: each spot's kernel beyond its core window, with the kernel's rotation. It is made on
// a grid along the mask's axes (u, v) = (cos t x - sin t y, sin t x + cos t y) with nodes one
// pixel apart, covering the frame: there the kernel is separable, so the spots' full kernels are
// one matrix product A diag(g) B^T (column k of A holds q(v - v_k), of B q(u - u_k), at the
// spot's own sub-node position), from which each spot's core square (the nodes within the core
// half width of its nearest node) is then subtracted; each pixel then reads the grid at its
// (u, v) by 6-point Lagrange interpolation (decode/calibrate/grid_read). At t = 0 the nodes are
// the pixels and the read is exact. Along the pixel axes instead (the kernel unrotated), the
// tails' long arms (sinc^2 along each axis) missed their rows by t x at x pixels from the spot:
// 7 px at 500 px for 0.8 deg, and the leak and the pinhole side took up the difference
// (docs/calibration.md). Each spot on its nearest node and a bilinear read, as before, moved
// the tails' fringes (6.6 px apart on the phone camera) by up to half a pixel and damped them by
// up to 11 %: the pinhole side came out 0.7 sigma small at 0.8 deg (docs/calibration.md).
// Far cheaper than an FFT convolution on a grid padded by the halo's reach.
Plane halo(const Problem& pb, const Params& p, double median_gain) {
    const double rh = halo_half_px(pb, p.v[kSide]);
    const int H = core_window_px(pb, p.v[kSide]);
    if (rh <= H) return Plane::Zero(pb.rows, pb.cols);
    const ProfileTable table(pb.mask.camera, pb.family, side_m(pb, p.v[kSide]), rh);
    const int h = static_cast<int>(std::floor(rh));
    const double ct = std::cos(p.v[kRot]), st = std::sin(p.v[kRot]);
    auto to_grid = [&](double x, double y) {
        return Eigen::Vector2d(ct * x - st * y, st * x + ct * y);
    };
    // The grid's nodes: the (u, v) box of the frame's corners, three nodes beyond (the read's
    // reach).
    double u_lo = 1e300, u_hi = -1e300, v_lo = 1e300, v_hi = -1e300;
    for (const double y : {0.0, pb.rows - 1.0})
        for (const double x : {0.0, pb.cols - 1.0}) {
            const Eigen::Vector2d g = to_grid(x, y);
            u_lo = std::min(u_lo, g.x());
            u_hi = std::max(u_hi, g.x());
            v_lo = std::min(v_lo, g.y());
            v_hi = std::max(v_hi, g.y());
        }
    const long u0 = static_cast<long>(std::floor(u_lo)) - 3,
               v0 = static_cast<long>(std::floor(v_lo)) - 3;
    const long nu = static_cast<long>(std::ceil(u_hi)) + 4 - u0,
               nv = static_cast<long>(std::ceil(v_hi)) + 4 - v0;
    struct Site {
        long v, u;         // nearest node, grid indices
        double fv, fu, g;  // position in grid indices, gain
        bool fitted;       // a fitted cell: its core is the model's window, not the halo's
    };
    std::vector<Site> sites;
    auto add = [&](const Eigen::Vector2d& z, double g, bool fitted) {
        const Eigen::Vector2d w = to_grid(z.x(), z.y());
        const double fv = w.y() - v0, fu = w.x() - u0;
        const long v = std::lround(fv), u = std::lround(fu);
        if (v < -h || u < -h || v > nv - 1 + h || u > nu - 1 + h || g == 0.0) return;
        sites.push_back({v, u, fv, fu, g, fitted});
    };
    for (std::size_t k = 0; k < pb.cells.size(); ++k)
        add(centre_of(pb, p.v, pb.cells[k]), p.g[k], true);
    for (const Cell& c : pb.outside) add(centre_of(pb, p.v, c), median_gain, false);
    const Eigen::Index K = static_cast<Eigen::Index>(sites.size());
    check_memory(double(K) * (nu + nv) * sizeof(double) + 2.0 * double(nu) * nv * sizeof(float),
                 "the calibration model's diffraction halo");
    // In single precision (twice the SIMD width): the halo holds a few percent of the light, so
    // its relative rounding of 1e-7 is far below any capture's noise.
    Eigen::MatrixXf A = Eigen::MatrixXf::Zero(nv, K), B = Eigen::MatrixXf::Zero(nu, K);
    for (Eigen::Index k = 0; k < K; ++k) {
        const Site& s = sites[static_cast<std::size_t>(k)];
        for (long v = std::max(0L, s.v - h); v <= std::min(nv - 1, s.v + h); ++v)
            A(v, k) = static_cast<float>(s.g * table.value(v - s.fv));
        for (long u = std::max(0L, s.u - h); u <= std::min(nu - 1, s.u + h); ++u)
            B(u, k) = static_cast<float>(table.value(u - s.fu));
    }
    GridF full(nv, nu);
    full.noalias() = A * B.transpose();
    // The fitted cells' cores are the model's windows; a cell beyond them (no window) keeps its
    // whole kernel here, so the part of its core that reaches into the frame is not lost.
    for (const Site& s : sites)
        for (long v = std::max(0L, s.v - H); s.fitted && v <= std::min(nv - 1, s.v + H); ++v) {
            const double a = s.g * table.value(v - s.fv);
            for (long u = std::max(0L, s.u - H); u <= std::min(nu - 1, s.u + H); ++u)
                full(v, u) -= static_cast<float>(a * table.value(u - s.fu));
        }
    Plane out(pb.rows, pb.cols);
    for (int r = 0; r < pb.rows; ++r)
        for (int c = 0; c < pb.cols; ++c) {
            const Eigen::Vector2d g = to_grid(c, r);
            out(r, c) = read_lagrange6(full, g.y() - v0, g.x() - u0);
        }
    return out;
}

struct Evaluation {
    Plane model;                  // B + L F + core spots + halo
    std::vector<Window> windows;  // one per fitted cell
    Plane d[kNonlinear];          // derivative planes of the model (with derivatives)
};

// The model at p; with `derivs` also the windows' kernel values and the nonlinear derivative
// planes. `fixed` holds the halo and the footprint for this round.
Evaluation evaluate(const Problem& pb, const Params& p, const Plane& foot, const Plane& halo_plane,
                    bool derivs) {
    Evaluation e;
    e.model = p.background + p.leak * foot + halo_plane;
    const double s = p.v[kSide];
    const int half = core_window_px(pb, s);
    const ProfileTable q(pb.mask.camera, pb.family, side_m(pb, s), half + 1.0);
    ProfileTable qs;
    if (derivs) {
        qs = ProfileTable(pb.mask.camera, pb.family, side_m(pb, s * (1 + kSideStep)), half + 1.0);
        for (auto& d : e.d) d = Plane::Zero(pb.rows, pb.cols);
    }
    const bool same_grid = derivs && q.same_grid(qs);
    const double ct = std::cos(p.v[kRot]), st = std::sin(p.v[kRot]);
    e.windows.resize(pb.cells.size());
    for (std::size_t k = 0; k < pb.cells.size(); ++k) {
        const Cell& cell = pb.cells[k];
        const Eigen::Vector2d z = centre_of(pb, p.v, cell);
        Window& w = e.windows[k];
        const int zr = static_cast<int>(std::lround(z.y())),
                  zc = static_cast<int>(std::lround(z.x()));
        w.r0 = std::max(0, zr - half);
        w.r1 = std::min(pb.rows - 1, zr + half);
        w.c0 = std::max(0, zc - half);
        w.c1 = std::min(pb.cols - 1, zc + half);
        if (w.empty()) continue;
        w.k.assign(static_cast<std::size_t>(w.r1 - w.r0 + 1) * w.width(), 0.0);
        const double g = p.g[k];
        // Chain rule from the spot centre to the lattice parameters.
        const double cc = cell.col - pb.ref_col, cr = cell.row - pb.ref_row;
        const double dxdt = -p.v[kPx] * st * cc + p.v[kPy] * ct * cr;
        const double dydt = -p.v[kPx] * ct * cc - p.v[kPy] * st * cr;
        const double dxdpx = ct * cc, dydpx = -st * cc;
        const double dxdpy = st * cr, dydpy = ct * cr;
        std::size_t idx = 0;
        for (int r = w.r0; r <= w.r1; ++r)
            for (int c = w.c0; c <= w.c1; ++c, ++idx) {
                const double dx = c - z.x(), dy = r - z.y();
                const double u = ct * dx - st * dy, v = st * dx + ct * dy;
                if (!derivs) {
                    const double kv = q.value(u) * q.value(v);
                    w.k[idx] = kv;
                    e.model(r, c) += g * kv;
                    continue;
                }
                double qu, du, qv, dv, su, sv;
                if (same_grid) {
                    q.value_slope_pair(qs, u, qu, du, su);
                    q.value_slope_pair(qs, v, qv, dv, sv);
                } else {
                    q.value_slope(u, qu, du);
                    q.value_slope(v, qv, dv);
                    su = qs.value(u);
                    sv = qs.value(v);
                }
                const double kv = qu * qv;
                w.k[idx] = kv;
                e.model(r, c) += g * kv;
                const double kx = -(du * qv * ct + qu * dv * st);  // dK / dx_k
                const double ky = du * qv * st - qu * dv * ct;     // dK / dy_k
                const double krot = -du * qv * v + qu * dv * u;    // the kernel's own rotation
                const double ks = (su * sv - kv) / (s * kSideStep);
                e.d[kX0](r, c) += g * kx;
                e.d[kY0](r, c) += g * ky;
                e.d[kRot](r, c) += g * (kx * dxdt + ky * dydt + krot);
                e.d[kPx](r, c) += g * (kx * dxdpx + ky * dydpx);
                e.d[kPy](r, c) += g * (kx * dxdpy + ky * dydpy);
                e.d[kSide](r, c) += g * ks;
            }
    }
    return e;
}

// Normal equations J^T W J and J^T W r over (nonlinear, gains, leak, background).
void normal_equations(const Problem& pb, const Evaluation& e, const Plane& w, const Plane& res,
                      const Plane& foot, Eigen::MatrixXd& A, Eigen::VectorXd& b) {
    const int G = static_cast<int>(pb.cells.size());
    const int P = kNonlinear + G + 2, iL = kNonlinear + G, iB = iL + 1;
    A = Eigen::MatrixXd::Zero(P, P);
    b = Eigen::VectorXd::Zero(P);
    const Plane wr = w * res;
    const bool derivs = e.d[0].size() > 0;
    {  // The full-frame sums in one pass over the pixels (per row, then added up).
        const Eigen::Index n = w.size();
        const double* pw = w.data();
        const double* pf = foot.data();
        const double* pr = wr.data();
        const double* pd[kNonlinear];
        for (int i = 0; i < kNonlinear; ++i) pd[i] = derivs ? e.d[i].data() : nullptr;
        double dd[kNonlinear][kNonlinear] = {}, dl[kNonlinear] = {}, db[kNonlinear] = {},
               dr[kNonlinear] = {};
        double ll = 0, lb = 0, bb = 0, rl = 0, rb = 0;
        for (Eigen::Index k = 0; k < n; ++k) {
            const double wk = pw[k], fk = pf[k], rk = pr[k], wf = wk * fk;
            ll += wf * fk;
            lb += wf;
            bb += wk;
            rl += fk * rk;
            rb += rk;
            if (!derivs) continue;
            double d[kNonlinear];
            for (int i = 0; i < kNonlinear; ++i) d[i] = pd[i][k];
            for (int i = 0; i < kNonlinear; ++i) {
                const double wd = wk * d[i];
                for (int j = i; j < kNonlinear; ++j) dd[i][j] += wd * d[j];
                dl[i] += wd * fk;
                db[i] += wd;
                dr[i] += d[i] * rk;
            }
        }
        for (int i = 0; i < kNonlinear; ++i) {
            for (int j = i; j < kNonlinear; ++j) A(i, j) = dd[i][j];
            A(i, iL) = dl[i];
            A(i, iB) = db[i];
            b(i) = dr[i];
        }
        A(iL, iL) = ll;
        A(iL, iB) = lb;
        A(iB, iB) = bb;
        b(iL) = rl;
        b(iB) = rb;
    }
    for (int k = 0; k < G; ++k) {
        const Window& wk = e.windows[k];
        if (wk.empty()) continue;
        const int ik = kNonlinear + k;
        std::size_t idx = 0;
        double s[kNonlinear] = {0, 0, 0, 0, 0, 0}, sl = 0, sb = 0, sr = 0, kk = 0;
        for (int r = wk.r0; r <= wk.r1; ++r)
            for (int c = wk.c0; c <= wk.c1; ++c, ++idx) {
                const double wkv = w(r, c) * wk.k[idx];
                if (derivs)
                    for (int i = 0; i < kNonlinear; ++i) s[i] += wkv * e.d[i](r, c);
                sl += wkv * foot(r, c);
                sb += wkv;
                sr += wk.k[idx] * wr(r, c);
                kk += wkv * wk.k[idx];
            }
        for (int i = 0; i < kNonlinear; ++i) A(i, ik) = s[i];
        A(ik, iL) = sl;
        A(ik, iB) = sb;
        A(ik, ik) = kk;
        b(ik) = sr;
        for (int l = k + 1; l < G; ++l) {
            const Window& wl = e.windows[l];
            if (wl.empty()) continue;
            const int r0 = std::max(wk.r0, wl.r0), r1 = std::min(wk.r1, wl.r1);
            const int c0 = std::max(wk.c0, wl.c0), c1 = std::min(wk.c1, wl.c1);
            if (r1 < r0 || c1 < c0) continue;
            double acc = 0.0;
            for (int r = r0; r <= r1; ++r) {
                const double* a =
                    &wk.k[static_cast<std::size_t>(r - wk.r0) * wk.width() + (c0 - wk.c0)];
                const double* bb =
                    &wl.k[static_cast<std::size_t>(r - wl.r0) * wl.width() + (c0 - wl.c0)];
                for (int c = 0; c <= c1 - c0; ++c) acc += w(r, c0 + c) * a[c] * bb[c];
            }
            A(ik, kNonlinear + l) = acc;
        }
    }
    A.triangularView<Eigen::StrictlyLower>() = A.transpose().triangularView<Eigen::StrictlyLower>();
}

double weighted_cost(const Plane& w, const Plane& frame, const Plane& model) {
    return (w * (frame - model).square()).sum();
}

void apply_step(Params& p, const Eigen::VectorXd& step, const std::vector<int>& free) {
    const int G = static_cast<int>(p.g.size());
    for (std::size_t f = 0; f < free.size(); ++f) {
        const int i = free[f];
        if (i < kNonlinear)
            p.v[i] += step(f);
        else if (i < kNonlinear + G)
            p.g[i - kNonlinear] += step(f);
        else if (i == kNonlinear + G)
            p.leak += step(f);
        else
            p.background += step(f);
    }
    p.v[kSide] = std::clamp(p.v[kSide], kMinSideScale, kMaxSideScale);
}

struct RoundResult {
    int iterations = 0;
    bool converged = false;
};

// Levenberg-Marquardt over the free parameters with the weights, footprint and halo fixed.
RoundResult levenberg_marquardt(const Problem& pb, Params& p, const std::vector<int>& free,
                                const Plane& w, const Plane& foot, const Plane& halo_plane,
                                int max_iterations,
                                const std::function<void(int, int)>* on_iteration = nullptr) {
    RoundResult rr;
    // Derivative planes only when a nonlinear parameter is free (the gains' columns are the
    // windows' kernel values).
    const bool need_d = std::any_of(free.begin(), free.end(), [](int i) { return i < kNonlinear; });
    Evaluation e = evaluate(pb, p, foot, halo_plane, need_d);
    double cost = weighted_cost(w, pb.frame, e.model);
    double lambda = 1e-3;
    int small_steps = 0;
    for (int it = 0; it < max_iterations; ++it) {
        ++rr.iterations;
        if (on_iteration && *on_iteration) (*on_iteration)(it + 1, max_iterations);
        Eigen::MatrixXd A;
        Eigen::VectorXd b;
        normal_equations(pb, e, w, pb.frame - e.model, foot, A, b);
        const int F = static_cast<int>(free.size());
        Eigen::MatrixXd Af(F, F);
        Eigen::VectorXd bf(F);
        for (int i = 0; i < F; ++i) {
            bf(i) = b(free[i]);
            for (int j = 0; j < F; ++j) Af(i, j) = A(free[i], free[j]);
        }
        // Marquardt's damping in the Jacobi-scaled system (columns span many decades: a gain's
        // against the rotation's), so every parameter is damped relative to its own curvature.
        const Eigen::VectorXd dscale = Af.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
        const Eigen::MatrixXd As = dscale.asDiagonal() * Af * dscale.asDiagonal();
        const Eigen::VectorXd bs = dscale.cwiseProduct(bf);
        bool accepted = false;
        for (int attempt = 0; attempt < 12 && !accepted; ++attempt) {
            Eigen::MatrixXd M = As;
            M.diagonal().array() += lambda + 1e-12;
            const Eigen::VectorXd step = dscale.cwiseProduct(M.ldlt().solve(bs));
            if (!step.allFinite()) {
                lambda *= 10;
                continue;
            }
            Params trial = p;
            apply_step(trial, step, free);
            // The first trial carries the derivatives (it is usually accepted and then serves
            // the next iteration); retries after a rejection do not.
            const bool with_derivs = need_d && attempt == 0;
            Evaluation te = evaluate(pb, trial, foot, halo_plane, with_derivs);
            const double tc = weighted_cost(w, pb.frame, te.model);
            if (tc <= cost) {
                const double gain = cost - tc;
                p = trial;
                cost = tc;
                lambda = std::max(lambda / 5, 1e-9);
                accepted = true;
                // Converged: a decrease below kConvergedChi2 in units of the cost per degree of
                // freedom (chi^2 when the weights are the noise model's: the step moved the
                // parameters by about a tenth of their standard error or less), from a step that
                // was not merely damped short (a heavily damped step decreases little anywhere)
                // or on kSmallSteps accepted steps in a row.
                const double per_dof =
                    cost / std::max(1.0, double(pb.frame.size()) - double(free.size()));
                small_steps = gain <= kConvergedChi2 * per_dof ? small_steps + 1 : 0;
                if (small_steps > 0 && (lambda < 1e-2 || small_steps >= kSmallSteps)) {
                    rr.converged = true;
                    return rr;
                }
                e = with_derivs || !need_d ? std::move(te)
                                           : evaluate(pb, p, foot, halo_plane, true);
            } else {
                lambda *= 5;
            }
        }
        if (!accepted) {
            rr.converged = true;  // no descent left at any damping: a minimum to rounding
            break;
        }
    }
    return rr;
}

// var = alpha max(m, 0) + beta from the residuals: robust variance per bin of the model's value
// (median of r^2 / 0.4549, the median of chi^2 with one degree of freedom), then a weighted
// straight line.
void fit_noise(const Plane& frame, const Plane& model, double& alpha, double& beta) {
    const Eigen::Index n = frame.size();
    std::vector<std::pair<double, double>> mr(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) {
        const double m = model.data()[i], r = frame.data()[i] - m;
        mr[static_cast<std::size_t>(i)] = {std::max(m, 0.0), r * r};
    }
    // The bins are consecutive ranges of the order by (m, r^2): placed by selection (each bin's
    // elements, not their order inside it, matter), O(n log kBins) instead of a full sort.
    constexpr int kBins = 24;
    const std::function<void(int, int)> split = [&](int b0, int b1) {  // bins [b0, b1)
        if (b1 - b0 < 2) return;
        const int bm = (b0 + b1) / 2;
        const auto first = mr.begin() + static_cast<std::ptrdiff_t>(mr.size() * b0 / kBins);
        const auto last = mr.begin() + static_cast<std::ptrdiff_t>(mr.size() * b1 / kBins);
        std::nth_element(first, mr.begin() + static_cast<std::ptrdiff_t>(mr.size() * bm / kBins),
                         last);
        split(b0, bm);
        split(bm, b1);
    };
    split(0, kBins);
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    std::vector<double> all;
    for (int b = 0; b < kBins; ++b) {
        const std::size_t lo = mr.size() * b / kBins, hi = mr.size() * (b + 1) / kBins;
        if (hi <= lo + 10) continue;
        std::vector<double> r2, m;
        for (std::size_t i = lo; i < hi; ++i) {
            m.push_back(mr[i].first);
            r2.push_back(mr[i].second);
        }
        const double var = median_of(r2) / 0.4549364;
        const double x = median_of(m);
        const double wgt = double(hi - lo);
        sw += wgt;
        sx += wgt * x;
        sy += wgt * var;
        sxx += wgt * x * x;
        sxy += wgt * x * var;
        all.push_back(var);
    }
    const double det = sw * sxx - sx * sx;
    alpha = det > 0 ? (sw * sxy - sx * sy) / det : 0.0;
    beta = det > 0 ? (sy - alpha * sx) / sw : sy / std::max(sw, 1.0);
    if (alpha < 0 || beta <= 0) {  // no Poisson term the data can show: a constant variance
        alpha = 0;
        beta = median_of(all);
    }
    beta = std::max(beta, 1e-30);
}

Plane weights_of(const Plane& model, double alpha, double beta) {
    return 1.0 / (alpha * model.max(0.0) + beta);
}

}  // namespace

namespace {

// The fit from `start`; with `start_only` only its first round (no halo, unweighted), returning
// the lattice alone.
ForwardFit fit_from(const Plane& frame, const Mask& mask, const LatticeStart& start,
                    const ForwardFitOptions& o, bool start_only) {
    const int rows = static_cast<int>(frame.rows()), cols = static_cast<int>(frame.cols());
    Problem pb{frame,
               mask,
               o,
               fit_family(mask.camera, parse_kernel_model(mask.psf.kernel.model, "kernel model")),
               {},
               {},
               0.5 * (start.pitch_x_px + start.pitch_y_px),
               rows,
               cols};
    Params p;
    p.v[kX0] = start.x0;
    p.v[kY0] = start.y0;
    p.v[kRot] = start.rotation_rad;
    p.v[kPx] = start.pitch_x_px;
    p.v[kPy] = start.pitch_y_px;
    p.v[kSide] = 1.0;
    const double reach_core = core_half_px(pb, 1.3), reach_halo = halo_half_px(pb, 1.0);
    const int n = mask.pattern.n;
    for (int tr = 0; tr < mask.pattern.tiles_rows; ++tr)
        for (int tc = 0; tc < mask.pattern.tiles_cols; ++tc)
            for (const Cell& c : mask.pattern.pinholes) {
                const Cell cell{c.row + tr * n, c.col + tc * n};
                const Eigen::Vector2d z = centre_of(pb, p.v, cell);
                auto within = [&](double m) {
                    return z.x() >= -m && z.y() >= -m && z.x() <= cols - 1 + m &&
                           z.y() <= rows - 1 + m;
                };
                if (within(reach_core - 1.0))
                    pb.cells.push_back(cell);
                else if (within(reach_halo))
                    pb.outside.push_back(cell);
            }
    std::sort(pb.cells.begin(), pb.cells.end());
    if (pb.cells.empty())
        throw InvalidInput("calibrate: no pinhole of the design images into the frame");
    const int G = static_cast<int>(pb.cells.size());
    {  // The pivot: the fitted cell nearest the mean of the fitted cells.
        double mr = 0, mc = 0;
        for (const Cell& c : pb.cells) {
            mr += c.row;
            mc += c.col;
        }
        const Cell ref{static_cast<int>(std::lround(mr / G)),
                       static_cast<int>(std::lround(mc / G))};
        const Eigen::Vector2d z = centre_of(pb, p.v, ref);
        p.v[kX0] = z.x();
        p.v[kY0] = z.y();
        pb.ref_row = ref.row;
        pb.ref_col = ref.col;
    }
    check_memory(double(G) * std::pow(2 * reach_core + 3, 2) * sizeof(double) +
                     12.0 * rows * cols * sizeof(double),
                 "the calibration model's spot windows");
    p.g.assign(G, 0.0);
    p.background = median_of(std::vector<double>(frame.data(), frame.data() + frame.size()));

    std::vector<int> linear, all;
    for (int i = 0; i < kNonlinear + G + 2; ++i) {
        all.push_back(i);
        if (i >= kNonlinear) linear.push_back(i);
    }
    const int iL = kNonlinear + G, iB = iL + 1;
    ForwardFit out;
    out.family = pb.family;
    Plane w = Plane::Ones(rows, cols);
    Plane foot = footprint(pb, p.v);
    Plane halo_plane = Plane::Zero(rows, cols);
    // Leak and background apart only with enough pixels outside the footprint.
    const double outside_px = (footprint(pb, p.v, false) < 0.5).count();
    if (outside_px < std::max<double>(o.min_outside_px, o.min_outside_fraction * foot.size())) {
        const int held = o.dark_subtracted ? iB : iL;
        if (o.dark_subtracted) p.background = 0.0;
        all.erase(std::find(all.begin(), all.end(), held));
        linear.erase(std::find(linear.begin(), linear.end(), held));
        out.leak_measured = o.dark_subtracted;
    }
    double median_gain = 0.0;
    double alpha = 0, beta = 1;
    bool leak_fixed = false, halo_current = false;
    // Gains, leak and background at the start's geometry (a linear problem).
    levenberg_marquardt(pb, p, linear, w, foot, halo_plane, 3);
    median_gain = median_of(p.g);
    for (int round = 0; round < kRounds; ++round) {
        // The first round fits without the halo: made from a start a few pixels off, the fixed
        // halo holds the fit near that start (a fixed point that can stop short of the truth).
        // From the second round on, a round whose end has a higher cost than its start (both
        // with their own halo and footprint, the round's weights) is undone: the halo held fixed
        // inside a round can lead the fit away from the self-consistent minimum.
        if (round > 0 && !halo_current) {
            halo_plane = halo(pb, p, median_gain);
            foot = footprint(pb, p.v);
        }
        const Params before = p;
        const double cost_before =
            round > 0 ? weighted_cost(w, frame, evaluate(pb, p, foot, halo_plane, false).model)
                      : 0.0;
        std::vector<int> free = all;
        if (leak_fixed) free.erase(std::find(free.begin(), free.end(), iL));
        const bool leak_free = std::find(free.begin(), free.end(), iL) != free.end();
        const RoundResult rr = levenberg_marquardt(pb, p, free, w, foot, halo_plane,
                                                   o.max_iterations, &o.on_iteration);
        out.iterations += rr.iterations;
        out.converged = rr.converged;
        if (leak_free && p.leak < 0) {  // the leak cannot be negative: refit on the bound
            p.leak = 0;
            leak_fixed = true;
            free.erase(std::find(free.begin(), free.end(), iL));
            const RoundResult again = levenberg_marquardt(pb, p, free, w, foot, halo_plane,
                                                          o.max_iterations, &o.on_iteration);
            out.iterations += again.iterations;
            out.converged = again.converged;
        }
        if (round > 0) {
            const Plane h = halo(pb, p, median_of(p.g));
            const Plane f = footprint(pb, p.v);
            if (weighted_cost(w, frame, evaluate(pb, p, f, h, false).model) > cost_before) {
                p = before;
            } else {
                halo_plane = h;
                foot = f;
            }
            halo_current = true;
        }
        if (start_only) {
            const Eigen::Vector2d origin = centre_of(pb, p.v, Cell{0, 0});
            out.lattice = {origin.x(), origin.y(), p.v[kRot], p.v[kPx], p.v[kPy]};
            return out;
        }
        median_gain = median_of(p.g);
        const Evaluation e = evaluate(pb, p, foot, halo_plane, false);
        fit_noise(frame, e.model, alpha, beta);
        w = weights_of(e.model, alpha, beta);
    }
    // Fisher information at the solution, with the final noise model. A gain's column is its
    // spot's core alone (its tails are in the halo, held fixed): the geometry's errors match the
    // Cramer-Rao bound of an independent renderer within 7 %, the leak's come out about 0.8 of
    // it (docs/calibration.md, Uncertainties). The halo and footprint
    // are those of p already: the last round either kept its end's (made at p) or was undone to
    // its start, whose own they were.
    const Evaluation e = evaluate(pb, p, foot, halo_plane, true);
    w = weights_of(e.model, alpha, beta);
    Eigen::MatrixXd A;
    Eigen::VectorXd b;
    const Plane res = frame - e.model;
    normal_equations(pb, e, w, res, foot, A, b);
    const int P = static_cast<int>(A.rows());
    const double dof = std::max(1.0, double(frame.size()) - P);
    out.chi2_reduced = (w * res.square()).sum() / dof;
    const double signal = (e.model - p.background).square().sum();
    out.unexplained =
        signal > 0 ? std::max(0.0, res.square().sum() - (1.0 / w).sum()) / signal : 1.0;
    // Covariance over the identifiable parameters (`all`: a leak held on its bound stays in).
    const int F = static_cast<int>(all.size());
    Eigen::MatrixXd Af(F, F);
    for (int i = 0; i < F; ++i)
        for (int j = 0; j < F; ++j) Af(i, j) = A(all[i], all[j]);
    const Eigen::VectorXd scale = Af.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd An = scale.asDiagonal() * Af * scale.asDiagonal();
    Eigen::MatrixXd covf = An.ldlt().solve(Eigen::MatrixXd::Identity(F, F));
    if (!covf.allFinite())
        throw RuntimeFailure("calibrate: the fit's Fisher information is singular");
    covf = scale.asDiagonal() * covf * scale.asDiagonal();
    covf *= std::max(out.chi2_reduced, 1e-12);
    Eigen::MatrixXd cov = Eigen::MatrixXd::Constant(P, P, std::numeric_limits<double>::quiet_NaN());
    for (int i = 0; i < F; ++i)
        for (int j = 0; j < F; ++j) cov(all[i], all[j]) = covf(i, j);
    auto sd = [&](int i) {
        return std::isnan(cov(i, i)) ? cov(i, i) : std::sqrt(std::max(cov(i, i), 0.0));
    };
    // Back from the pivot to cell (0, 0): position and its covariance through the linear map
    // (x0, y0) = pivot - A (ref_col, ref_row).
    const Eigen::Vector2d origin = centre_of(pb, p.v, Cell{0, 0});
    out.lattice = {origin.x(), origin.y(), p.v[kRot], p.v[kPx], p.v[kPy]};
    Eigen::Matrix<double, 2, 5> jo = Eigen::Matrix<double, 2, 5>::Zero();
    {
        const double ct = std::cos(p.v[kRot]), st = std::sin(p.v[kRot]);
        const double cc = -pb.ref_col, cr = -pb.ref_row;
        jo(0, kX0) = 1;
        jo(1, kY0) = 1;
        jo(0, kRot) = -p.v[kPx] * st * cc + p.v[kPy] * ct * cr;
        jo(1, kRot) = -p.v[kPx] * ct * cc - p.v[kPy] * st * cr;
        jo(0, kPx) = ct * cc;
        jo(1, kPx) = -st * cc;
        jo(0, kPy) = st * cr;
        jo(1, kPy) = ct * cr;
    }
    const Eigen::Matrix2d cov_origin = jo * cov.topLeftCorner<5, 5>() * jo.transpose();
    out.side_scale = p.v[kSide];
    out.side_m = side_m(pb, p.v[kSide]);
    out.x0_sigma = std::sqrt(std::max(cov_origin(0, 0), 0.0));
    out.y0_sigma = std::sqrt(std::max(cov_origin(1, 1), 0.0));
    out.rotation_sigma_rad = sd(kRot);
    out.pitch_x_sigma_px = sd(kPx);
    out.pitch_y_sigma_px = sd(kPy);
    out.side_scale_sigma = sd(kSide);
    out.leak = p.leak;
    out.leak_sigma = sd(iL);
    out.leak_at_bound = leak_fixed;
    out.background = p.background;
    out.background_sigma = sd(iL + 1);
    out.noise_alpha = alpha;
    out.noise_beta = beta;
    out.model = e.model;
    // Missing pinholes: the upper bound g + z sigma below half the median gain in frame.
    const double margin = 0.5 * std::max(p.v[kPx], p.v[kPy]);
    std::vector<double> in_gains;
    for (int k = 0; k < G; ++k) {
        FittedPinhole f;
        f.mask_cell = pb.cells[k];
        const Eigen::Vector2d z = centre_of(pb, p.v, f.mask_cell);
        f.x = z.x();
        f.y = z.y();
        f.gain = p.g[k];
        f.gain_sigma = sd(kNonlinear + k);
        f.in_frame = z.x() >= margin && z.y() >= margin && z.x() <= cols - 1 - margin &&
                     z.y() <= rows - 1 - margin;
        if (f.in_frame) in_gains.push_back(f.gain);
        out.pinholes.push_back(f);
    }
    out.median_gain = median_of(in_gains);
    // One-sided z of the false-alarm rate (inverse normal tail by bisection on erfc).
    const double fa = std::clamp(o.missing_false_alarm, 1e-15, 0.5);
    double lo = 0, hi = 40;
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(mid / std::numbers::sqrt2) > fa ? lo : hi) = mid;
    }
    out.missing_z = 0.5 * (lo + hi);
    for (auto& f : out.pinholes)
        f.missing = f.in_frame && f.gain + out.missing_z * f.gain_sigma < 0.5 * out.median_gain;
    return out;
}

// The model of a rows x cols frame at a fit's parameters: with `psf` the calibrated PSF (the
// spots of the pinholes not missing, gains max(g, 0), no leak or background, sum 1), else the
// whole model B + L F + spots (every fitted pinhole at its gain, cells beyond the frame at the
// median gain in the halo) as fit_from's rounds evaluate it.
Plane model_of_fit(const ForwardFit& fit, const Mask& mask, int rows, int cols,
                   const ForwardFitOptions& o, bool psf) {
    const Plane no_frame;
    Problem pb{no_frame,
               mask,
               o,
               fit.family,
               {},
               {},
               0.5 * (fit.lattice.pitch_x_px + fit.lattice.pitch_y_px),
               rows,
               cols};
    Params p;
    p.v[kX0] = fit.lattice.x0;
    p.v[kY0] = fit.lattice.y0;
    p.v[kRot] = fit.lattice.rotation_rad;
    p.v[kPx] = fit.lattice.pitch_x_px;
    p.v[kPy] = fit.lattice.pitch_y_px;
    p.v[kSide] = fit.side_scale;
    for (const auto& f : fit.pinholes) {
        if (psf && f.missing) continue;
        pb.cells.push_back(f.mask_cell);
        p.g.push_back(psf ? std::max(f.gain, 0.0) : f.gain);
    }
    // Open cells the fit did not hold (their core off the frame) whose halo reaches it.
    const double reach_halo = halo_half_px(pb, fit.side_scale);
    const int n = mask.pattern.n;
    for (int tr = 0; tr < mask.pattern.tiles_rows; ++tr)
        for (int tc = 0; tc < mask.pattern.tiles_cols; ++tc)
            for (const Cell& c : mask.pattern.pinholes) {
                const Cell cell{c.row + tr * n, c.col + tc * n};
                if (std::any_of(fit.pinholes.begin(), fit.pinholes.end(),
                                [&](const FittedPinhole& f) { return f.mask_cell == cell; }))
                    continue;
                const Eigen::Vector2d z = centre_of(pb, p.v, cell);
                if (z.x() >= -reach_halo && z.y() >= -reach_halo &&
                    z.x() <= cols - 1 + reach_halo && z.y() <= rows - 1 + reach_halo)
                    pb.outside.push_back(cell);
            }
    if (psf) {
        const Plane zero = Plane::Zero(rows, cols);
        Plane m = evaluate(pb, p, zero, halo(pb, p, fit.median_gain), false).model;
        const double s = m.sum();
        if (s > 0) m /= s;
        return m;
    }
    p.leak = fit.leak;
    p.background = fit.background;
    return evaluate(pb, p, footprint(pb, p.v), halo(pb, p, median_of(p.g)), false).model;
}

}  // namespace

int first_pass_binning(double pitch_px, int rows, int cols) {
    const int b = static_cast<int>(std::floor(pitch_px / kBinnedCellPx));
    return b >= 2 && std::min(rows, cols) >= kMinBinnedFramePx ? b : 1;
}

Plane bin_frame(const Plane& frame, int b) {
    const int R = static_cast<int>(frame.rows()) / b, C = static_cast<int>(frame.cols()) / b;
    Plane binned = Plane::Zero(R, C);
    for (int r = 0; r < R * b; ++r)
        for (int c = 0; c < C * b; ++c) binned(r / b, c / b) += frame(r, c);
    return binned;
}

LatticeStart to_binned(const LatticeStart& l, int b) {
    return {(l.x0 + 0.5) / b - 0.5, (l.y0 + 0.5) / b - 0.5, l.rotation_rad, l.pitch_x_px / b,
            l.pitch_y_px / b};
}

LatticeStart from_binned(const LatticeStart& l, int b) {
    return {(l.x0 + 0.5) * b - 0.5, (l.y0 + 0.5) * b - 0.5, l.rotation_rad, l.pitch_x_px * b,
            l.pitch_y_px * b};
}

// Two passes: the first round from the start (no halo) refines the lattice, and the whole fit
// starts again from there, so the fitted cells, the pivot and the halo's first estimate come from
// a lattice within a fraction of a pixel (from the start's, a few pixels off, the rounds with the
// halo held fixed can settle on a false minimum).
// A large capture with wide cells (b = floor(pitch / kBinnedCellPx) >= 2, the short side at
// least kMinBinnedFramePx) makes its first pass binned b x b: the model's pixels b times larger,
// the halo's reach the same on the sensor, b^2 times fewer pixels per iteration. The second pass
// fits the capture itself from the binned pass's lattice (moved to the capture's pixels). A
// binned second pass was biased: on the phone-like camera's 1024 x 1024 crop (16 px per cell,
// tests/python/test_calibrate_coverage.py) the pinhole side came out -4.9 and -2.1 sigma and the
// optical density +3.4 and +1.6 sigma off on seeds 1 and 2; fitted at full resolution -1.9 / +0.8
// and +0.2 / -0.7, the same figures as a fit without any binned pass, in 1.3x the binned fit's
// time (scripts/calibrate-coverage.py).
ForwardFit fit_forward_model(const Plane& frame, const Mask& mask, const LatticeStart& start,
                             const ForwardFitOptions& o) {
    const int b =
        first_pass_binning(0.5 * (start.pitch_x_px + start.pitch_y_px),
                           static_cast<int>(frame.rows()), static_cast<int>(frame.cols()));
    if (b < 2) {
        const ForwardFit first = fit_from(frame, mask, start, o, true);
        ForwardFit out = fit_from(frame, mask, first.lattice, o, false);
        out.iterations += first.iterations;
        return out;
    }
    const Plane binned = bin_frame(frame, b);
    Mask coarse = mask;
    coarse.camera.pixel_pitch_m *= b;
    ForwardFitOptions ob = o;
    ob.halo_cap_px = std::max(1, o.halo_cap_px / b);
    const ForwardFit first = fit_from(binned, coarse, to_binned(start, b), ob, true);
    ForwardFit out = fit_from(frame, mask, from_binned(first.lattice, b), o, false);
    out.iterations += first.iterations;
    return out;
}

Plane fitted_psf(const ForwardFit& fit, const Mask& mask, int rows, int cols,
                 const ForwardFitOptions& o) {
    return model_of_fit(fit, mask, rows, cols, o, true);
}

}  // namespace pinmask::calibrate
