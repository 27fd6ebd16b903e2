// An independent forward model of a point-source capture through a perturbed tiled mask, written
// for the tests (it shares no code with calibrate/): each open, non-missing mask cell (R, C)
// makes a square spot of side `spot_px` (rotated with the mask) blurred by a Gaussian of
// `blur_px`, centred at
//   x = x0 + px cos(t) C - py sin(t) R,   y = y0 + px sin(t) C + py cos(t) R,
// integrated over each pixel by 4 x 4 sub-samples (the truth is defined by this model, noise
// free). Leak: a constant `leak` inside the mask's footprint (cells -1/2 .. n tiles - 1/2);
// dark: a constant everywhere; Gaussian noise with sigma = peak / 10^(snr_db / 20) where peak is
// the spot's flat-top level `amplitude`.
#pragma once

#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "core/image.hpp"
#include "design/pattern.hpp"

namespace pinmask::test {

struct PointSourceScene {
    Pattern pattern;
    int rows = 300, cols = 300;
    double x0 = 20.0, y0 = 22.0;
    double rotation_deg = 0.0;
    double pitch_x = 8.0, pitch_y = 8.0;
    double spot_px = 8.0, blur_px = 0.5;
    double amplitude = 1000.0;
    double leak = 0.0, dark = 0.0;
    double snr_db = 60.0;
    std::set<Cell> missing;  // mask cells (R, C)
    unsigned seed = 1;
};

inline double box_blur_1d(double u, double side, double sigma) {
    const double s = sigma * std::sqrt(2.0);
    return 0.5 * (std::erf((u + side / 2) / s) - std::erf((u - side / 2) / s));
}

inline std::vector<std::pair<Cell, std::pair<double, double>>> spot_sites(
    const PointSourceScene& m) {
    const double t = m.rotation_deg * M_PI / 180.0;
    std::vector<std::pair<Cell, std::pair<double, double>>> out;
    const int n = m.pattern.n;
    for (int tr = 0; tr < m.pattern.tiles_rows; ++tr)
        for (int tc = 0; tc < m.pattern.tiles_cols; ++tc)
            for (const Cell& c : m.pattern.pinholes) {
                const int R = c.row + tr * n, C = c.col + tc * n;
                if (m.missing.count({R, C})) continue;
                out.push_back({{R, C},
                               {m.x0 + m.pitch_x * std::cos(t) * C - m.pitch_y * std::sin(t) * R,
                                m.y0 + m.pitch_x * std::sin(t) * C + m.pitch_y * std::cos(t) * R}});
            }
    return out;
}

// The noise-free spot image (amplitude-scaled, no leak or dark).
inline Plane point_source_spots(const PointSourceScene& m) {
    Plane img = Plane::Zero(m.rows, m.cols);
    const double t = m.rotation_deg * M_PI / 180.0, ct = std::cos(t), st = std::sin(t);
    const int reach = static_cast<int>(std::ceil(m.spot_px * 0.75 + 4 * m.blur_px + 2));
    for (const auto& [cell, xy] : spot_sites(m)) {
        const auto [cx, cy] = xy;
        for (int r = int(cy) - reach; r <= int(cy) + reach; ++r)
            for (int c = int(cx) - reach; c <= int(cx) + reach; ++c) {
                if (r < 0 || c < 0 || r >= m.rows || c >= m.cols) continue;
                double v = 0.0;
                for (int a = 0; a < 4; ++a)
                    for (int b = 0; b < 4; ++b) {
                        const double dx = c - 0.375 + 0.25 * b - cx, dy = r - 0.375 + 0.25 * a - cy;
                        const double u = ct * dx + st * dy, w = -st * dx + ct * dy;
                        v += box_blur_1d(u, m.spot_px, m.blur_px) *
                             box_blur_1d(w, m.spot_px, m.blur_px);
                    }
                img(r, c) += m.amplitude * v / 16.0;
            }
    }
    return img;
}

// The capture: spots + leak in the footprint + dark + noise.
inline Plane point_source_capture(const PointSourceScene& m) {
    Plane img = point_source_spots(m);
    const double t = m.rotation_deg * M_PI / 180.0, ct = std::cos(t), st = std::sin(t);
    const int mr = m.pattern.n * m.pattern.tiles_rows, mc = m.pattern.n * m.pattern.tiles_cols;
    std::mt19937_64 rng(m.seed);
    std::normal_distribution<double> noise(0.0, m.amplitude / std::pow(10.0, m.snr_db / 20.0));
    for (int r = 0; r < m.rows; ++r)
        for (int c = 0; c < m.cols; ++c) {
            const double dx = c - m.x0, dy = r - m.y0;
            const double C = (ct * dx + st * dy) / m.pitch_x, R = (-st * dx + ct * dy) / m.pitch_y;
            if (C >= -0.5 && R >= -0.5 && C <= mc - 0.5 && R <= mr - 0.5) img(r, c) += m.leak;
            img(r, c) += m.dark + noise(rng);
        }
    return img;
}

// Normalised (mean-removed) correlation of two planes of one size.
inline double normalised_correlation(const Plane& a, const Plane& b) {
    const Plane da = a - a.mean(), db = b - b.mean();
    return (da * db).sum() / std::sqrt((da * da).sum() * (db * db).sum());
}

}  // namespace pinmask::test
