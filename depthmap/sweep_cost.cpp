#include "depthmap/sweep_cost.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/fft.hpp"
#include "core/field_names.hpp"
#include "decode/psf2otf.hpp"
#include "design/psf_exact.hpp"

namespace pinmask {
namespace {

// Running sums along one axis of a row-major plane, cyclic, one pass per line.
Plane box_rows(const Plane& p, int window) {
    const Eigen::Index r = p.rows(), c = p.cols();
    const int h = window / 2;
    Plane out(r, c);
    for (Eigen::Index j = 0; j < c; ++j) {
        double s = 0;
        for (int k = -h; k <= h; ++k) s += p(((k % r) + r) % r, j);
        for (Eigen::Index i = 0; i < r; ++i) {
            out(i, j) = s / window;
            s += p((i + h + 1) % r, j) - p(((i - h) % r + r) % r, j);
        }
    }
    return out;
}

}  // namespace

Plane box_mean(const Plane& p, int window) {
    const Plane t = box_rows(p, window);
    // Columns: box the transpose (rows of the transposed plane).
    const Plane tt = t.transpose();
    return box_rows(tt, window).transpose();
}

PlaneCost sweep_cost(const Plane& capture, const Mask& mask, double u, double nsr, int window) {
    const int rows = static_cast<int>(capture.rows()), cols = static_cast<int>(capture.cols());
    if (rows < 8 || cols < 8) {
        throw invalid_field("capture", std::to_string(rows) + "x" + std::to_string(cols),
                            "must be at least 8 x 8 pixels");
    }
    if (!is_all_finite(capture)) throw invalid_field("capture", "", "holds NaN or Inf");
    if (!(nsr > 0.0) || !std::isfinite(nsr)) {
        throw invalid_field(field_ref("wiener_nsr"), std::to_string(nsr), "must be finite and > 0");
    }
    if (window < 3 || window % 2 == 0 || window > std::min(rows, cols)) {
        throw invalid_field(field_ref("cost_window"), std::to_string(window),
                            "must be odd, >= 3 and at most the capture's smaller side (" +
                                std::to_string(std::min(rows, cols)) + ")");
    }
    ExactPsfOptions eo;
    eo.object_distance_m = u;
    eo.rows = rows;
    eo.cols = cols;
    const Plane psf = exact_psf(mask, eo);
    const Fft2 fft(rows, cols);
    const ComplexPlane pf = fft.forward(capture);
    const ComplexPlane h = psf2otf(psf / psf.sum(), rows, cols);
    const ComplexPlane g = h.conjugate() / (h.abs2() + nsr);
    PlaneCost out;
    out.estimate = fft.inverse(g * pf);
    // capture - h (*) estimate = ifft(nsr / (|H|^2 + nsr) P): what the plane cannot explain.
    const ComplexPlane residual = pf * (nsr / (h.abs2() + nsr));
    out.cost = box_mean(fft.inverse(residual).square(), window);
    return out;
}

}  // namespace pinmask
