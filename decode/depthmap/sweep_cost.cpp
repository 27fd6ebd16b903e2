#include "decode/depthmap/sweep_cost.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/psf2otf.hpp"
#include "design/psf/psf_exact.hpp"

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

namespace {

void check_inputs(const Plane& capture, double nsr, int window) {
    const Eigen::Index rows = capture.rows(), cols = capture.cols();
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
}

constexpr double kPriorEps = 1e-4;
constexpr double kPi = std::numbers::pi;

// The evidence of the header for the capture's half spectrum pf and the plane's OTF h.
double evidence_of(const ComplexPlane& pf, const ComplexPlane& h, int rows, int cols) {
    const double n = double(rows) * double(cols);
    const Eigen::Index half = pf.cols();
    // Each half-spectrum column stands for itself and its mirror, except l = 0 and l = C/2.
    auto weight = [&](Eigen::Index l) { return (l == 0 || 2 * l == cols) ? 1.0 : 2.0; };
    auto lambda = [&](Eigen::Index k, Eigen::Index l) {
        const double sy = std::sin(kPi * double(k) / rows), sx = std::sin(kPi * double(l) / cols);
        return 4.0 * sy * sy + 4.0 * sx * sx;
    };
    double noise_sum = 0, noise_count = 0, power = 0, model = 0;
    for (Eigen::Index k = 0; k < pf.rows(); ++k) {
        for (Eigen::Index l = 0; l < half; ++l) {
            const double w = weight(l), p = std::norm(pf(k, l)) / n, lam = lambda(k, l);
            power += w * p;
            model += w * std::norm(h(k, l)) / (lam + kPriorEps);
            if (lam > 6.0) {
                noise_sum += w * p;
                noise_count += w;
            }
        }
    }
    const double s2 = noise_count > 0 ? noise_sum / noise_count : 0.0;
    const double a = std::max(power - s2 * n, 1e-12) / model;
    double total = 0;
    for (Eigen::Index k = 0; k < pf.rows(); ++k) {
        for (Eigen::Index l = 0; l < half; ++l) {
            const double d =
                std::norm(h(k, l)) * a / (lambda(k, l) + kPriorEps) + std::max(s2, 1e-300);
            total += weight(l) * (std::norm(pf(k, l)) / n / d + std::log(d));
        }
    }
    return total / n;
}

PlaneCost cost_of(const Plane& capture, const Plane& psf, double nsr, int window) {
    const int rows = static_cast<int>(capture.rows()), cols = static_cast<int>(capture.cols());
    const Fft2 fft(rows, cols);
    const ComplexPlane pf = fft.forward(capture);
    const ComplexPlane h = psf2otf(psf / psf.sum(), rows, cols);
    const ComplexPlane g = h.conjugate() / (h.abs2() + nsr);
    PlaneCost out;
    out.estimate = fft.inverse(g * pf);
    // capture - h (*) estimate = ifft(nsr / (|H|^2 + nsr) P): what the plane cannot explain.
    const ComplexPlane residual = pf * (nsr / (h.abs2() + nsr));
    out.cost = box_mean(fft.inverse(residual).square(), window);
    out.evidence = evidence_of(pf, h, rows, cols);
    return out;
}

}  // namespace

PlaneCost sweep_cost(const Plane& capture, const Mask& mask, double u, double nsr, int window) {
    check_inputs(capture, nsr, window);
    ExactPsfOptions eo;
    eo.object_distance_m = u;
    eo.rows = static_cast<int>(capture.rows());
    eo.cols = static_cast<int>(capture.cols());
    return cost_of(capture, exact_psf(mask, eo), nsr, window);
}

PlaneCost sweep_cost(const Plane& capture, const Plane& psf, double nsr, int window) {
    check_inputs(capture, nsr, window);
    if (psf.rows() < 1 || psf.cols() < 1 || psf.rows() > capture.rows() ||
        psf.cols() > capture.cols()) {
        throw invalid_field(
            field_ref("psf_stack"), std::to_string(psf.rows()) + "x" + std::to_string(psf.cols()),
            "a PSF must be at most the capture's size (" + std::to_string(capture.rows()) + "x" +
                std::to_string(capture.cols()) + ")");
    }
    if (!is_all_finite(psf) || psf.minCoeff() < 0.0 || !(psf.sum() > 0.0))
        throw invalid_field(field_ref("psf_stack"), "",
                            "a PSF must be finite, non-negative and hold some light");
    return cost_of(capture, psf, nsr, window);
}

}  // namespace pinmask
