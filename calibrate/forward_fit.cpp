#include "calibrate/forward_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "calibrate/profile_table.hpp"
#include "calibrate/spots.hpp"
#include "core/error.hpp"
#include "core/fft.hpp"
#include "core/number_format.hpp"
#include "core/resource_limits.hpp"

namespace pinmask::calibrate {

namespace {

constexpr int kNonlinear = 6;  // x0, y0, t, px, py, s
enum { kX0 = 0, kY0 = 1, kRot = 2, kPx = 3, kPy = 4, kSide = 5 };
constexpr double kSideStep = 1e-4;  // forward difference of the side scale
constexpr double kMinSideScale = 0.2, kMaxSideScale = 5.0;
constexpr int kRounds = 3;
constexpr double kConvergedChi2 = 1e-2;
constexpr int kSmallSteps = 3;
// The first pass runs on a binned capture when cells are at least 2 kBinnedCellPx pixels wide
// and the frame at least kMinBinnedFramePx on its short side.
constexpr double kBinnedCellPx = 8.0;
constexpr int kMinBinnedFramePx =
    1024;  // unweighted, then weighted with the noise model refitted twice

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

double core_half_px(const Problem& pb, double scale) {
    if (pb.family == KernelModel::kBox)
        return profile_support_px(pb.mask.camera, pb.family, side_m(pb, scale), 1.0, 1e9) + 0.5;
    return pb.o.core_cells * pb.cell_px;
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

// Footprint of the tiled mask (anti-aliased over one pixel along each mask axis).
Plane footprint(const Problem& pb, const double* v) {
    const double ct = std::cos(v[kRot]), st = std::sin(v[kRot]);
    const double ncol = pb.mask.pattern.n * pb.mask.pattern.tiles_cols;
    const double nrow = pb.mask.pattern.n * pb.mask.pattern.tiles_rows;
    Plane f(pb.rows, pb.cols);
    for (int r = 0; r < pb.rows; ++r)
        for (int c = 0; c < pb.cols; ++c) {
            const double dx = c - v[kX0], dy = r - v[kY0];
            // Pixels along the axes from cell (0, 0)'s spot centre ((x0, y0) is the pivot's).
            const double a = ct * dx - st * dy + pb.ref_col * v[kPx];
            const double b = st * dx + ct * dy + pb.ref_row * v[kPy];
            const double fa = std::clamp(a + 0.5 * v[kPx] + 0.5, 0.0, 1.0) *
                              std::clamp((ncol - 0.5) * v[kPx] - a + 0.5, 0.0, 1.0);
            const double fb = std::clamp(b + 0.5 * v[kPy] + 0.5, 0.0, 1.0) *
                              std::clamp((nrow - 0.5) * v[kPy] - b + 0.5, 0.0, 1.0);
            f(r, c) = fa * fb;
        }
    return f;
}

// The halo: each spot's kernel beyond its core window, by FFT on a padded grid (spots split
// bilinearly onto pixels; the tail is evaluated along the pixel axes).
Plane halo(const Problem& pb, const Params& p, double median_gain) {
    const double rh = halo_half_px(pb, p.v[kSide]);
    const int H = core_window_px(pb, p.v[kSide]);
    if (rh <= H) return Plane::Zero(pb.rows, pb.cols);
    const ProfileTable full(pb.mask.camera, pb.family, side_m(pb, p.v[kSide]), rh);
    const int pad = static_cast<int>(std::ceil(rh)) + 2;
    const int R = pb.rows + 2 * pad, C = pb.cols + 2 * pad;
    check_memory(6.0 * R * C * sizeof(double), "the calibration model's diffraction halo");
    Plane deltas = Plane::Zero(R, C);
    // Each spot on its nearest pixel: the tail then starts exactly where its core window ends.
    auto splat = [&](const Eigen::Vector2d& q, double g) {
        const long r = std::lround(q.y()) + pad, c = std::lround(q.x()) + pad;
        if (r < 0 || c < 0 || r >= R || c >= C) return;
        deltas(r, c) += g;
    };
    for (std::size_t k = 0; k < pb.cells.size(); ++k)
        splat(centre_of(pb, p.v, pb.cells[k]), p.g[k]);
    for (const Cell& c : pb.outside) splat(centre_of(pb, p.v, c), median_gain);
    Plane tail = Plane::Zero(R, C);
    const int h = static_cast<int>(std::floor(rh));
    std::vector<double> q(2 * h + 1);
    for (int k = -h; k <= h; ++k) q[k + h] = full.value(k);
    for (int dy = -h; dy <= h; ++dy)
        for (int dx = -h; dx <= h; ++dx) {
            if (std::max(std::abs(dx), std::abs(dy)) <= H) continue;
            tail((dy + R) % R, (dx + C) % C) = q[dy + h] * q[dx + h];
        }
    Fft2 fft(R, C);
    const ComplexPlane D = fft.forward(deltas), T = fft.forward(tail);
    const Plane conv = fft.inverse((D * T).eval());
    return conv.block(pad, pad, pb.rows, pb.cols);
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
                double qu, du, qv, dv;
                q.value_slope(u, qu, du);
                q.value_slope(v, qv, dv);
                const double kv = qu * qv;
                w.k[idx] = kv;
                e.model(r, c) += g * kv;
                const double kx = -(du * qv * ct + qu * dv * st);  // dK / dx_k
                const double ky = du * qv * st - qu * dv * ct;     // dK / dy_k
                const double krot = -du * qv * v + qu * dv * u;    // the kernel's own rotation
                const double ks = (qs.value(u) * qs.value(v) - kv) / (s * kSideStep);
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
    const Plane wr = w * res, wf = w * foot;
    for (int i = 0; i < kNonlinear; ++i) {
        const Plane wd = w * e.d[i];
        for (int j = i; j < kNonlinear; ++j) A(i, j) = (wd * e.d[j]).sum();
        A(i, iL) = (wd * foot).sum();
        A(i, iB) = wd.sum();
        b(i) = (e.d[i] * wr).sum();
    }
    A(iL, iL) = (wf * foot).sum();
    A(iL, iB) = wf.sum();
    A(iB, iB) = w.sum();
    b(iL) = (foot * wr).sum();
    b(iB) = wr.sum();
    for (int k = 0; k < G; ++k) {
        const Window& wk = e.windows[k];
        if (wk.empty()) continue;
        const int ik = kNonlinear + k;
        std::size_t idx = 0;
        double s[kNonlinear] = {0, 0, 0, 0, 0, 0}, sl = 0, sb = 0, sr = 0, kk = 0;
        for (int r = wk.r0; r <= wk.r1; ++r)
            for (int c = wk.c0; c <= wk.c1; ++c, ++idx) {
                const double wkv = w(r, c) * wk.k[idx];
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
    Evaluation e = evaluate(pb, p, foot, halo_plane, true);
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
            const bool with_derivs = attempt == 0;
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
                e = with_derivs ? std::move(te) : evaluate(pb, p, foot, halo_plane, true);
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
    std::sort(mr.begin(), mr.end());
    constexpr int kBins = 24;
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
    const double outside_px = (foot < 0.5).count();
    if (outside_px < std::max<double>(o.min_outside_px, o.min_outside_fraction * foot.size())) {
        const int held = o.dark_subtracted ? iB : iL;
        if (o.dark_subtracted) p.background = 0.0;
        all.erase(std::find(all.begin(), all.end(), held));
        linear.erase(std::find(linear.begin(), linear.end(), held));
        out.leak_measured = o.dark_subtracted;
    }
    // Gains, leak and background at the start's geometry (a linear problem).
    levenberg_marquardt(pb, p, linear, w, foot, halo_plane, 3);
    double median_gain = median_of(p.g);
    double alpha = 0, beta = 1;
    bool leak_fixed = false, halo_current = false;
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
    // Fisher information at the solution, with the final noise model.
    halo_plane = halo(pb, p, median_gain);
    foot = footprint(pb, p.v);
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

}  // namespace

// Two passes: the first round from the start (no halo) refines the lattice, and the whole fit
// starts again from there, so the fitted cells, the pivot and the halo's first estimate come from
// a lattice within a fraction of a pixel (from the start's, a few pixels off, the rounds with the
// halo held fixed can settle on a false minimum).
ForwardFit fit_forward_model(const Plane& frame, const Mask& mask, const LatticeStart& start,
                             const ForwardFitOptions& o) {
    // A large capture with wide cells: the first pass on the capture binned b x b (b = pitch /
    // kBinnedCellPx, the model's pixels b times larger: the pixel-integrated kernel stays exact),
    // b^2 times fewer pixels per iteration.
    const double pitch = 0.5 * (start.pitch_x_px + start.pitch_y_px);
    const int b = static_cast<int>(std::floor(pitch / kBinnedCellPx));
    LatticeStart refined;
    int first_iterations = 0;
    if (b >= 2 && std::min(frame.rows(), frame.cols()) >= kMinBinnedFramePx) {
        const int R = static_cast<int>(frame.rows()) / b, C = static_cast<int>(frame.cols()) / b;
        Plane binned = Plane::Zero(R, C);
        for (int r = 0; r < R * b; ++r)
            for (int c = 0; c < C * b; ++c) binned(r / b, c / b) += frame(r, c);
        Mask coarse = mask;
        coarse.camera.pixel_pitch_m *= b;
        // Pixel (i, j) of the binned frame covers pixels b i .. b i + b - 1: index coordinate
        // x of the capture is (x + 1/2) / b - 1/2 there.
        auto to_binned = [b](double x) { return (x + 0.5) / b - 0.5; };
        auto from_binned = [b](double x) { return (x + 0.5) * b - 0.5; };
        const LatticeStart s{to_binned(start.x0), to_binned(start.y0), start.rotation_rad,
                             start.pitch_x_px / b, start.pitch_y_px / b};
        const ForwardFit f = fit_from(binned, coarse, s, o, true);
        refined = {from_binned(f.lattice.x0), from_binned(f.lattice.y0), f.lattice.rotation_rad,
                   f.lattice.pitch_x_px * b, f.lattice.pitch_y_px * b};
        first_iterations = f.iterations;
    } else {
        const ForwardFit first = fit_from(frame, mask, start, o, true);
        refined = first.lattice;
        first_iterations = first.iterations;
    }
    ForwardFit out = fit_from(frame, mask, refined, o, false);
    out.iterations += first_iterations;
    return out;
}

Plane fitted_psf(const ForwardFit& fit, const Mask& mask, int rows, int cols,
                 const ForwardFitOptions& o) {
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
        if (f.missing) continue;
        pb.cells.push_back(f.mask_cell);
        p.g.push_back(std::max(f.gain, 0.0));
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
    const Plane zero = Plane::Zero(rows, cols);
    const Plane h = halo(pb, p, fit.median_gain);
    Params q = p;
    q.leak = q.background = 0;
    Plane psf = evaluate(pb, q, zero, h, false).model;
    const double s = psf.sum();
    if (s > 0) psf /= s;
    return psf;
}

}  // namespace pinmask::calibrate
