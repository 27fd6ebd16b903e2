#include "decode/wiener.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/fft.hpp"
#include "decode/psf2otf.hpp"

namespace pinmask {
namespace {

void check_floor(double floor) {
    if (!(floor >= 0.0) || !std::isfinite(floor)) {
        throw invalid_field("denominator_floor", std::to_string(floor), "must be finite and >= 0");
    }
}

// conj(h) / max(|h|^2 + nsr, floor), 0 where that denominator is 0.
std::complex<double> wiener_gain(std::complex<double> h, double nsr, double floor) {
    const double denom = std::max(std::norm(h) + nsr, floor);
    return denom > 0.0 ? std::conj(h) / denom : std::complex<double>(0.0, 0.0);
}

}  // namespace

WienerFilter::WienerFilter(int rows, int cols, ComplexPlane g)
    : rows_(rows), cols_(cols), fft_(rows, cols), g_(std::move(g)) {
    finish();
}

void WienerFilter::finish() {
    const double inv_n = 1.0 / (static_cast<double>(rows_) * cols_);
    g_scaled_ = g_ * inv_n;
    g_scaled_f_ = g_scaled_.cast<std::complex<float>>();
}

WienerFilter::WienerFilter(const Plane& psf, int rows, int cols, double nsr,
                           double denominator_floor)
    : rows_(rows), cols_(cols), fft_(rows, cols) {
    if (!(nsr >= 0.0) || !std::isfinite(nsr)) {
        throw invalid_field("nsr", std::to_string(nsr), "must be finite and >= 0");
    }
    check_floor(denominator_floor);
    const ComplexPlane h = psf2otf(psf, rows, cols);
    g_.resize(h.rows(), h.cols());
    for (Eigen::Index i = 0; i < h.size(); ++i) {
        g_.data()[i] = wiener_gain(h.data()[i], nsr, denominator_floor);
    }
    finish();
}

WienerFilter::WienerFilter(const Plane& psf, int rows, int cols, const Plane& nsr_per_frequency,
                           double denominator_floor)
    : rows_(rows), cols_(cols), fft_(rows, cols) {
    const Plane& nsr = nsr_per_frequency;
    if (nsr.rows() != rows || nsr.cols() != cols) {
        throw invalid_field(
            "nsr_per_frequency", std::to_string(nsr.rows()) + " x " + std::to_string(nsr.cols()),
            "must have the working size " + std::to_string(rows) + " x " + std::to_string(cols));
    }
    if (!is_all_finite(nsr) || (nsr < 0.0).any()) {
        throw invalid_field("nsr_per_frequency", "array", "every value must be finite and >= 0");
    }
    check_floor(denominator_floor);
    const ComplexPlane h = psf2otf(psf, rows, cols);
    g_.resize(h.rows(), h.cols());
    // Hermitian part of G: conj(G(-k)) = conj(H(k)) / max(|H(k)|^2 + NSR(-k), floor).
    for (Eigen::Index k = 0; k < h.rows(); ++k) {
        const Eigen::Index mk = (rows - k) % rows;
        for (Eigen::Index l = 0; l < h.cols(); ++l) {
            const Eigen::Index ml = (cols - l) % cols;
            g_(k, l) = 0.5 * (wiener_gain(h(k, l), nsr(k, l), denominator_floor) +
                              wiener_gain(h(k, l), nsr(mk, ml), denominator_floor));
        }
    }
    finish();
}

WienerFilter WienerFilter::from_half_spectrum(ComplexPlane g_half, int rows, int cols) {
    if (rows < 1 || cols < 1 || g_half.rows() != rows || g_half.cols() != cols / 2 + 1) {
        throw invalid_field(
            "g_half", std::to_string(g_half.rows()) + " x " + std::to_string(g_half.cols()),
            "must be the half spectrum of " + std::to_string(rows) + " x " + std::to_string(cols));
    }
    return WienerFilter(rows, cols, std::move(g_half));
}

Plane WienerFilter::apply(const Plane& capture) const {
    Plane out;
    Workspace ws;
    apply(capture, out, ws);
    return out;
}

void WienerFilter::apply(const Plane& capture, Plane& out, Workspace& ws) const {
    if (capture.rows() != rows_ || capture.cols() != cols_) {
        throw invalid_field(
            "capture", std::to_string(capture.rows()) + " x " + std::to_string(capture.cols()),
            "must match the filter size " + std::to_string(rows_) + " x " + std::to_string(cols_));
    }
    fft_.forward(capture, ws.spectrum);
    ws.spectrum *= g_scaled_;  // with the 1/N of the inverse transform
    fft_.inverse_unscaled_destroy(ws.spectrum, out);
}

void WienerFilter::apply_single(const Plane& capture, Plane& out, WorkspaceF& ws) const {
    if (capture.rows() != rows_ || capture.cols() != cols_) {
        throw invalid_field(
            "capture", std::to_string(capture.rows()) + " x " + std::to_string(capture.cols()),
            "must match the filter size " + std::to_string(rows_) + " x " + std::to_string(cols_));
    }
    const Fft2f fft(rows_, cols_);
    ws.in = capture.cast<float>();
    fft.forward(ws.in, ws.spectrum);
    ws.spectrum *= g_scaled_f_;
    fft.inverse_unscaled_destroy(ws.spectrum, ws.out);
    out = ws.out.cast<double>();
}

double WienerFilter::gain() const { return g_.size() == 0 ? 0.0 : g_.abs().maxCoeff(); }

}  // namespace pinmask
