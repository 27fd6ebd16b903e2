// An independent forward model of a point-source capture through a perturbed tiled mask, written
// for the tests (it shares no code with decode/calibrate/): each open, non-missing mask cell (R, C)
// makes a spot (rotated with the mask) centred at
//   x = x0 + px cos(t) C + py sin(t) R,   y = y0 - px sin(t) C + py cos(t) R
// (t counter-clockwise on screen with rows running down: scipy.ndimage.rotate's sense), either
//   a square of side `spot_px` blurred by a Gaussian of `blur_px` (erf profile), or
//   the diffraction pattern of a square pinhole behind the lens: per axis the intensity
//     a |J|^2 / 4, J = int_{-1}^{1} exp(i pi (N s^2 - a x s)) ds (x in pixels along the mask's
//     axis, N = fresnel_n, a = v_per_px), by composite Simpson quadrature written here,
// integrated over each pixel by sub-samples (the truth is defined by this model, noise free).
// Leak: a constant `leak` inside the mask's footprint (cells -1/2 .. n tiles - 1/2); dark: a
// constant everywhere; Gaussian noise with sigma = peak / 10^(snr_db / 20) where peak is the
// spot's flat-top level `amplitude`; or (photon_noise) Poisson counts, Gaussian read noise and
// an ADC of adc_bits with `adc_gain` electrons per count.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "core/image/image.hpp"
#include "design/pattern/pattern.hpp"

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
    // Diffraction spots instead of the blurred box (v_per_px > 0); amplitude is then the flux of
    // one pinhole (counts summed over its whole pattern), spot_px and blur_px are unused.
    double fresnel_n = 0.0, v_per_px = 0.0;
    double diffraction_reach_px = 0.0;  // spots rendered out to this (0: the whole frame)
    std::map<Cell, double> gains;       // per mask cell flux factor (default 1)
    bool photon_noise = false;          // Poisson photons + read noise + ADC instead of snr_db
    double read_noise_e = 3.0, adc_gain = 1.0;
    int adc_bits = 12;
};

// Per-axis diffraction intensity of a square pinhole (see above), density per unit v.
class PinholeProfile1d {
  public:
    PinholeProfile1d(double fresnel_n) : n_(fresnel_n) {}
    double operator()(double v) const {
        constexpr int m = 600;  // Simpson intervals over s in [-1, 1]
        const double h = 2.0 / m;
        std::complex<double> acc = 0.0;
        for (int k = 0; k <= m; ++k) {
            const double s = -1.0 + k * h;
            const double w = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
            const double ph = M_PI * (n_ * s * s - v * s);
            acc += w * std::complex<double>(std::cos(ph), std::sin(ph));
        }
        acc *= h / 3.0;
        return std::norm(acc) / 4.0;
    }

  private:
    double n_;
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
                               {m.x0 + m.pitch_x * std::cos(t) * C + m.pitch_y * std::sin(t) * R,
                                m.y0 - m.pitch_x * std::sin(t) * C + m.pitch_y * std::cos(t) * R}});
            }
    return out;
}

// The noise-free spot image (amplitude-scaled, no leak or dark).
inline Plane point_source_spots(const PointSourceScene& m) {
    Plane img = Plane::Zero(m.rows, m.cols);
    const double t = m.rotation_deg * M_PI / 180.0, ct = std::cos(t), st = std::sin(t);
    auto gain_of = [&](const Cell& c) {
        const auto it = m.gains.find(c);
        return it == m.gains.end() ? 1.0 : it->second;
    };
    if (m.v_per_px > 0) {
        // Density per pixel a h(a x) on a fine table (step 1/64 px), 4 x 4 sub-samples per pixel.
        const PinholeProfile1d h(m.fresnel_n);
        const double reach = m.diffraction_reach_px > 0 ? m.diffraction_reach_px
                                                        : double(std::max(m.rows, m.cols)) + 2.0;
        const double step = 1.0 / 64.0;
        const int nt = static_cast<int>(std::ceil((reach + 2.0) / step));
        std::vector<double> table(2 * nt + 1);
        for (int k = -nt; k <= nt; ++k) table[k + nt] = m.v_per_px * h(m.v_per_px * k * step);
        auto dens = [&](double x) {
            const double u = x / step + nt;
            if (u < 0 || u >= 2 * nt) return 0.0;
            const int k = static_cast<int>(u);
            const double f = u - k;
            return table[k] + f * (table[k + 1] - table[k]);
        };
        for (const auto& [cell, xy] : spot_sites(m)) {
            const auto [cx, cy] = xy;
            const double amp = m.amplitude * gain_of(cell);
            const int r0 = std::max(0, int(std::floor(cy - reach)));
            const int r1 = std::min(m.rows - 1, int(std::ceil(cy + reach)));
            const int c0 = std::max(0, int(std::floor(cx - reach)));
            const int c1 = std::min(m.cols - 1, int(std::ceil(cx + reach)));
            for (int r = r0; r <= r1; ++r)
                for (int c = c0; c <= c1; ++c) {
                    double v = 0.0;
                    for (int a = 0; a < 4; ++a)
                        for (int b = 0; b < 4; ++b) {
                            const double dx = c - 0.375 + 0.25 * b - cx;
                            const double dy = r - 0.375 + 0.25 * a - cy;
                            v += dens(ct * dx - st * dy) * dens(st * dx + ct * dy);
                        }
                    img(r, c) += amp * v / 16.0;
                }
        }
        return img;
    }
    const int reach = static_cast<int>(std::ceil(m.spot_px * 0.75 + 4 * m.blur_px + 2));
    for (const auto& [cell, xy] : spot_sites(m)) {
        const auto [cx, cy] = xy;
        const double amp = m.amplitude * gain_of(cell);
        for (int r = int(cy) - reach; r <= int(cy) + reach; ++r)
            for (int c = int(cx) - reach; c <= int(cx) + reach; ++c) {
                if (r < 0 || c < 0 || r >= m.rows || c >= m.cols) continue;
                double v = 0.0;
                for (int a = 0; a < 4; ++a)
                    for (int b = 0; b < 4; ++b) {
                        const double dx = c - 0.375 + 0.25 * b - cx, dy = r - 0.375 + 0.25 * a - cy;
                        const double u = ct * dx - st * dy, w = st * dx + ct * dy;
                        v += box_blur_1d(u, m.spot_px, m.blur_px) *
                             box_blur_1d(w, m.spot_px, m.blur_px);
                    }
                img(r, c) += amp * v / 16.0;
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
    std::normal_distribution<double> unit(0.0, 1.0);
    const double full = std::pow(2.0, m.adc_bits) - 1;
    for (int r = 0; r < m.rows; ++r)
        for (int c = 0; c < m.cols; ++c) {
            const double dx = c - m.x0, dy = r - m.y0;
            const double C = (ct * dx - st * dy) / m.pitch_x, R = (st * dx + ct * dy) / m.pitch_y;
            if (C >= -0.5 && R >= -0.5 && C <= mc - 0.5 && R <= mr - 0.5) img(r, c) += m.leak;
            if (!m.photon_noise) {
                img(r, c) += m.dark + noise(rng);
                continue;
            }
            // Electrons: Poisson of the mean (light + dark), read noise; counts: ADC.
            const double mean_e = std::max(0.0, (img(r, c) + m.dark) * m.adc_gain);
            double e = m.read_noise_e * unit(rng);
            if (mean_e > 0) e += double(std::poisson_distribution<long long>(mean_e)(rng));
            img(r, c) = std::clamp(std::round(e / m.adc_gain), 0.0, full);
        }
    return img;
}

// Normalised (mean-removed) correlation of two planes of one size.
inline double normalised_correlation(const Plane& a, const Plane& b) {
    const Plane da = a - a.mean(), db = b - b.mean();
    return (da * db).sum() / std::sqrt((da * da).sum() * (db * db).sum());
}

}  // namespace pinmask::test
