#include "decode/calibrate/subpixel.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace pinmask::calibrate {

double lanczos3(double t) {
    t = std::abs(t);
    if (t < 1e-12) return 1.0;
    if (t >= kLanczosA) return 0.0;
    const double pt = std::numbers::pi * t;
    return kLanczosA * std::sin(pt) * std::sin(pt / kLanczosA) / (pt * pt);
}

namespace {

// Weights of the 2a taps for a fractional offset f in [0, 1): value at (base + f) from samples
// base - a + 1 .. base + a, normalised to sum 1 (exact reproduction of constants).
std::array<double, 2 * kLanczosA> taps(double f) {
    std::array<double, 2 * kLanczosA> w{};
    double s = 0.0;
    for (int k = 0; k < 2 * kLanczosA; ++k) {
        w[k] = lanczos3(f - (k - kLanczosA + 1));
        s += w[k];
    }
    for (double& v : w) v /= s;
    return w;
}

int wrap_index(int i, int n) { return ((i % n) + n) % n; }

}  // namespace

void add_kernel(Plane& target, const Plane& kernel, double ky, double kx, double y, double x,
                double weight, bool wrap) {
    // Target pixel (r, c) takes the kernel's interpolated value at (r - (y - ky), c - (x - kx)).
    const double dy = y - ky, dx = x - kx;
    const double fy0 = std::floor(dy), fx0 = std::floor(dx);
    const double fy = dy - fy0, fx = dx - fx0;  // kernel coordinate = r - fy0 - fy
    // r - dy = (r - fy0 - 1) + (1 - fy): base index r - fy0 - 1, fraction 1 - fy (when fy > 0).
    const bool sy = fy > 0, sx = fx > 0;
    const auto wy = taps(sy ? 1.0 - fy : 0.0), wx = taps(sx ? 1.0 - fx : 0.0);
    const int by = static_cast<int>(fy0) + (sy ? 1 : 0), bx = static_cast<int>(fx0) + (sx ? 1 : 0);
    const int kr = static_cast<int>(kernel.rows()), kc = static_cast<int>(kernel.cols());
    const int tr = static_cast<int>(target.rows()), tc = static_cast<int>(target.cols());
    // Rows of the target touched: r with base = r - by in [-a, kr - 1 + a].
    Plane rows_done = Plane::Zero(kr + 2 * kLanczosA, kc);  // interpolated along rows first
    for (int r = -kLanczosA; r < kr + kLanczosA; ++r) {
        for (int k = 0; k < 2 * kLanczosA; ++k) {
            const int src = r - kLanczosA + 1 + k;
            if (src < 0 || src >= kr || wy[k] == 0.0) continue;
            rows_done.row(r + kLanczosA) += wy[k] * kernel.row(src);
        }
    }
    for (int r = 0; r < rows_done.rows(); ++r) {
        int trow = r - kLanczosA + by;
        if (wrap) trow = wrap_index(trow, tr);
        if (trow < 0 || trow >= tr) continue;
        for (int c = -kLanczosA; c < kc + kLanczosA; ++c) {
            double v = 0.0;
            for (int k = 0; k < 2 * kLanczosA; ++k) {
                const int src = c - kLanczosA + 1 + k;
                if (src < 0 || src >= kc) continue;
                v += wx[k] * rows_done(r, src);
            }
            if (v == 0.0) continue;
            int tcol = c + bx;
            if (wrap) tcol = wrap_index(tcol, tc);
            if (tcol < 0 || tcol >= tc) continue;
            target(trow, tcol) += weight * v;
        }
    }
}

Plane sample_window(const Plane& source, double y, double x, int half) {
    const int size = 2 * half + 1;
    Plane out = Plane::Zero(size, size);
    const double fy0 = std::floor(y), fx0 = std::floor(x);
    const auto wy = taps(y - fy0), wx = taps(x - fx0);
    const int sr = static_cast<int>(source.rows()), sc = static_cast<int>(source.cols());
    for (int r = 0; r < size; ++r) {
        const int base_r = static_cast<int>(fy0) + r - half;
        for (int c = 0; c < size; ++c) {
            const int base_c = static_cast<int>(fx0) + c - half;
            double v = 0.0;
            for (int a = 0; a < 2 * kLanczosA; ++a) {
                const int rr = base_r - kLanczosA + 1 + a;
                if (rr < 0 || rr >= sr) continue;
                double row_v = 0.0;
                for (int b = 0; b < 2 * kLanczosA; ++b) {
                    const int cc = base_c - kLanczosA + 1 + b;
                    if (cc < 0 || cc >= sc) continue;
                    row_v += wx[b] * source(rr, cc);
                }
                v += wy[a] * row_v;
            }
            out(r, c) = v;
        }
    }
    return out;
}

void centroid(const Plane& p, double& y, double& x) {
    double s = 0.0, sy = 0.0, sx = 0.0;
    for (int r = 0; r < p.rows(); ++r)
        for (int c = 0; c < p.cols(); ++c) {
            s += p(r, c);
            sy += p(r, c) * r;
            sx += p(r, c) * c;
        }
    y = s != 0.0 ? sy / s : 0.0;
    x = s != 0.0 ? sx / s : 0.0;
}

}  // namespace pinmask::calibrate
