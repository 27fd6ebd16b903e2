#include "design/psf/psf_exact.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/units.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/psf.hpp"

namespace pinmask {
namespace {

// Window sides accepted (a 65536-pixel side is already far beyond any sensor).
constexpr int kMaxWindowSide = 65536;

Camera at_distance(const Camera& c, double u) {
    Camera out = c;
    out.object_distance_m = u;
    return out;
}

// Adds weight * kernel with its first pixel's edge at continuous (y0, x0), area-resampled.
void add_resampled(Plane& out, const Plane& k, double y0, double x0, double weight) {
    const double fy = std::floor(y0), fx = std::floor(x0);
    const double ty = y0 - fy, tx = x0 - fx;  // fractional shifts in [0, 1)
    const long long r0 = static_cast<long long>(fy), c0 = static_cast<long long>(fx);
    const double wy[2] = {1.0 - ty, ty}, wx[2] = {1.0 - tx, tx};
    for (Eigen::Index i = 0; i < k.rows(); ++i) {
        for (int a = 0; a < 2; ++a) {
            const long long r = r0 + i + a;
            if (r < 0 || r >= out.rows() || wy[a] == 0.0) continue;
            for (Eigen::Index j = 0; j < k.cols(); ++j) {
                const double v = weight * wy[a] * k(i, j);
                for (int b = 0; b < 2; ++b) {
                    const long long c = c0 + j + b;
                    if (c < 0 || c >= out.cols() || wx[b] == 0.0) continue;
                    out(r, c) += v * wx[b];
                }
            }
        }
    }
}

// Adds weight * row (x) col, each normalised to its kept sum (as make_kernel normalises a cut
// support), at their absolute origins; pixels off the window are dropped.
void add_box_spot(Plane& out, const PixelProfile& row, const PixelProfile& col, double weight) {
    double sr = 0.0, sc = 0.0;
    for (double v : row.values) sr += v;
    for (double v : col.values) sc += v;
    const double scale = weight / (sr * sc);
    for (std::size_t i = 0; i < row.values.size(); ++i) {
        const long long r = static_cast<long long>(row.origin) + static_cast<long long>(i);
        if (r < 0 || r >= out.rows() || row.values[i] == 0.0) continue;
        for (std::size_t j = 0; j < col.values.size(); ++j) {
            const long long c = static_cast<long long>(col.origin) + static_cast<long long>(j);
            if (c < 0 || c >= out.cols()) continue;
            out(r, c) += scale * row.values[i] * col.values[j];
        }
    }
}

}  // namespace

SpotCentre exact_spot_centre(const Mask& m, double u, int rows, int cols, int cell_row,
                             int cell_col) {
    const double pitch_px =
        magnification_at_u(at_distance(m.camera, u)) * m.camera.pinhole_m / m.camera.pixel_pitch_m;
    const double nt_r = static_cast<double>(m.pattern.n) * m.pattern.tiles_rows;
    const double nt_c = static_cast<double>(m.pattern.n) * m.pattern.tiles_cols;
    return {rows / 2.0 + (cell_row + 0.5 - nt_r / 2.0) * pitch_px,
            cols / 2.0 + (cell_col + 0.5 - nt_c / 2.0) * pitch_px};
}

Plane exact_psf(const Mask& m, const ExactPsfOptions& o) {
    validate(m.camera);
    validate(m.pattern, /*allow_spacing_violations=*/true);
    if (m.pattern.pinholes.empty()) {
        throw invalid_field("pattern pinholes", "0", "the PSF needs at least one pinhole");
    }
    check_object_distance(m.camera, o.object_distance_m, "object_distance_m");
    const int rows = o.rows > 0 ? o.rows : m.camera.sensor_rows;
    const int cols = o.cols > 0 ? o.cols : m.camera.sensor_cols;
    if (o.rows < 0 || o.cols < 0 || rows > kMaxWindowSide || cols > kMaxWindowSide) {
        throw invalid_field("size", std::to_string(o.rows) + "x" + std::to_string(o.cols),
                            "each side must be between 1 and " + std::to_string(kMaxWindowSide));
    }
    const Camera cam = at_distance(m.camera, o.object_distance_m);
    if (magnification_at_u(cam) == 0.0) {
        throw invalid_field("object_distance_m", format_length(o.object_distance_m),
                            "gives 1 - f/f' + f/u = 0: every pinhole images to the same spot");
    }
    check_memory(double(rows) * cols * 8.0, "the " + std::to_string(rows) + " x " +
                                                std::to_string(cols) + " exact-geometry PSF");
    // The kernel over its own support, not cut to one period as the cyclic PSF's must be (a
    // spot wider than the period folds onto itself there; over a frame it does not): at most
    // what reaches across the window from a spot at its edge.
    check_psf_memory(m.pattern.n, m.psf.pixels_per_cell, 0, 0);
    KernelOptions ko = o.kernel;
    ko.max_width_px = std::min(ko.max_width_px, 2 * std::max(rows, cols) + 1);
    const Kernel k = make_kernel(cam, m.psf.kernel, m.psf.pixels_per_cell, ko);
    const int ppc = m.psf.pixels_per_cell;
    Plane out = Plane::Zero(rows, cols);
    const double weight = 1.0 / static_cast<double>(m.pattern.pinholes.size());
    // The box is geometric (no wavelength): each spot integrated exactly over the pixels at its
    // own centre with side |M(u)| d / w, so its size follows u and no resampling blurs it. Other
    // kernels are moved to the spot centre by area resampling.
    const bool box = k.model == KernelModel::kBox;
    const double spot_px =
        box ? std::fabs(magnification_at_u(cam)) * cam.pinhole_m / cam.pixel_pitch_m : 0.0;
    for (int tr = 0; tr < m.pattern.tiles_rows; ++tr) {
        for (int tc = 0; tc < m.pattern.tiles_cols; ++tc) {
            for (const Cell& cell : m.pattern.pinholes) {
                const SpotCentre s =
                    exact_spot_centre(m, o.object_distance_m, rows, cols,
                                      tr * m.pattern.n + cell.row, tc * m.pattern.n + cell.col);
                if (box) {
                    add_box_spot(out, box_pixel_profile_at(spot_px, s.row, ko),
                                 box_pixel_profile_at(spot_px, s.col, ko), weight);
                } else {
                    // Kernel pixel i covers [y0 + i, y0 + i + 1): its centre ppc/2 - origin
                    // from y0.
                    add_resampled(out, k.values, s.row - ppc / 2.0 + k.origin_row,
                                  s.col - ppc / 2.0 + k.origin_col, weight);
                }
            }
        }
    }
    return out;
}

}  // namespace pinmask
