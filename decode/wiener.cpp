#include "decode/wiener.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/fft.hpp"
#include "decode/precision.hpp"
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

void check_otf(const ComplexPlane& otf, int rows, int cols) {
    if (rows < 1 || cols < 1 || otf.rows() != rows || otf.cols() != cols / 2 + 1) {
        throw invalid_field(
            "otf", std::to_string(otf.rows()) + " x " + std::to_string(otf.cols()),
            "must be the half spectrum of " + std::to_string(rows) + " x " + std::to_string(cols));
    }
}

// spectrum <- g_scaled .* spectrum (g_scaled = G / N), gathering the requested sums of
// SpectralSums over the unscaled estimate spectrum X = N g_scaled P, in double.
template <class T>
void filter_with_sums(
    Eigen::Array<std::complex<T>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& spectrum,
    const Eigen::Array<std::complex<T>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& g_scaled,
    int rows, int cols, SpectralSums& sums) {
    using Cd = std::complex<double>;
    const double n = static_cast<double>(rows) * cols;
    const int hc = cols / 2 + 1;
    const ComplexPlane* H = sums.otf;
    const Plane* w = sums.weight;
    if (H) check_otf(*H, rows, cols);
    if (w && (w->rows() != rows || w->cols() != hc)) {
        throw invalid_field(
            "weight", std::to_string(w->rows()) + " x " + std::to_string(w->cols()),
            "must be the half spectrum of " + std::to_string(rows) + " x " + std::to_string(cols));
    }
    double res2 = 0.0, pen = 0.0;
    for (int k = 0; k < rows; ++k) {
        for (int l = 0; l < hc; ++l) {
            const Eigen::Index i = Eigen::Index(k) * hc + l;
            const std::complex<T> p = spectrum.data()[i];
            const std::complex<T> xs = g_scaled.data()[i] * p;
            spectrum.data()[i] = xs;
            const Cd x = Cd(xs) * n;
            if (H) {
                const double m = (l == 0 || 2 * l == cols) ? 1.0 : 2.0;
                res2 += m * std::norm(H->data()[i] * x - Cd(p));
            }
            if (w) pen += w->data()[i] * std::norm(x);
        }
    }
    sums.residual2 = res2 / n;
    sums.penalty = pen / n;
}

}  // namespace

WienerFilter::WienerFilter(int rows, int cols, ComplexPlane g)
    : rows_(rows), cols_(cols), fft_(rows, cols), g_(std::move(g)) {
    finish();
}

void WienerFilter::finish() {
    const double inv_n = 1.0 / (static_cast<double>(rows_) * cols_);
    g_scaled_ = g_ * inv_n;
    // The float copy only where --precision auto decodes in float (kSinglePrecisionMinPixels):
    // below it apply_single converts into its workspace per call (a warm 128 x 128 Wiener
    // decode spent 5 % making a copy it never used).
    if (static_cast<long long>(rows_) * cols_ >= kSinglePrecisionMinPixels)
        g_scaled_f_ = g_scaled_.cast<std::complex<float>>();
}

WienerFilter WienerFilter::from_otf(const ComplexPlane& otf, int rows, int cols, double nsr,
                                    double denominator_floor) {
    if (!(nsr >= 0.0) || !std::isfinite(nsr)) {
        throw invalid_field("nsr", std::to_string(nsr), "must be finite and >= 0");
    }
    check_floor(denominator_floor);
    check_otf(otf, rows, cols);
    ComplexPlane g(otf.rows(), otf.cols());
    for (Eigen::Index i = 0; i < otf.size(); ++i) {
        g.data()[i] = wiener_gain(otf.data()[i], nsr, denominator_floor);
    }
    return WienerFilter(rows, cols, std::move(g));
}

WienerFilter WienerFilter::from_otf(const ComplexPlane& h, int rows, int cols,
                                    const Plane& nsr_per_frequency, double denominator_floor) {
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
    check_otf(h, rows, cols);
    ComplexPlane g(h.rows(), h.cols());
    // Hermitian part of G: conj(G(-k)) = conj(H(k)) / max(|H(k)|^2 + NSR(-k), floor).
    for (Eigen::Index k = 0; k < h.rows(); ++k) {
        const Eigen::Index mk = (rows - k) % rows;
        for (Eigen::Index l = 0; l < h.cols(); ++l) {
            const Eigen::Index ml = (cols - l) % cols;
            g(k, l) = 0.5 * (wiener_gain(h(k, l), nsr(k, l), denominator_floor) +
                             wiener_gain(h(k, l), nsr(mk, ml), denominator_floor));
        }
    }
    return WienerFilter(rows, cols, std::move(g));
}

WienerFilter::WienerFilter(const Plane& psf, int rows, int cols, double nsr,
                           double denominator_floor)
    : WienerFilter(from_otf(psf2otf(psf, rows, cols), rows, cols, nsr, denominator_floor)) {}

WienerFilter::WienerFilter(const Plane& psf, int rows, int cols, const Plane& nsr_per_frequency,
                           double denominator_floor)
    : WienerFilter(
          from_otf(psf2otf(psf, rows, cols), rows, cols, nsr_per_frequency, denominator_floor)) {}

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

void WienerFilter::check_capture(const Plane& capture) const {
    if (capture.rows() != rows_ || capture.cols() != cols_) {
        throw invalid_field(
            "capture", std::to_string(capture.rows()) + " x " + std::to_string(capture.cols()),
            "must match the filter size " + std::to_string(rows_) + " x " + std::to_string(cols_));
    }
}

void WienerFilter::apply(const Plane& capture, Plane& out, Workspace& ws,
                         SpectralSums* sums) const {
    check_capture(capture);
    fft_.forward(capture, ws.spectrum);
    if (sums) {
        filter_with_sums(ws.spectrum, g_scaled_, rows_, cols_, *sums);
    } else {
        ws.spectrum *= g_scaled_;  // with the 1/N of the inverse transform
    }
    fft_.inverse_unscaled_destroy(ws.spectrum, out);
}

void WienerFilter::apply_single(const Plane& capture, Plane& out, WorkspaceF& ws,
                                SpectralSums* sums) const {
    check_capture(capture);
    const Fft2f fft(rows_, cols_);
    ws.in = capture.cast<float>();
    fft.forward(ws.in, ws.spectrum);
    if (g_scaled_f_.size() == 0) ws.filter = g_scaled_.cast<std::complex<float>>();
    const ComplexPlaneF& g = g_scaled_f_.size() == 0 ? ws.filter : g_scaled_f_;
    if (sums) {
        filter_with_sums(ws.spectrum, g, rows_, cols_, *sums);
    } else {
        ws.spectrum *= g;
    }
    fft.inverse_unscaled_destroy(ws.spectrum, ws.out);
    out = ws.out.cast<double>();
}

Plane half_spectrum_multiplicity(int rows, int cols) {
    const int hc = cols / 2 + 1;
    Plane m = Plane::Constant(rows, hc, 2.0);
    m.col(0).setConstant(1.0);
    if (cols % 2 == 0) m.col(hc - 1).setConstant(1.0);
    return m;
}

Plane fold_full_spectrum_weight(const Plane& full) {
    const Eigen::Index rows = full.rows(), cols = full.cols();
    const Eigen::Index hc = cols / 2 + 1;
    Plane out(rows, hc);
    for (Eigen::Index k = 0; k < rows; ++k) {
        for (Eigen::Index l = 0; l < hc; ++l) {
            const Eigen::Index ml = (cols - l) % cols;
            // The partner column -l lies in the half spectrum only for l = 0 and l = cols / 2.
            out(k, l) = full(k, l) + (ml >= hc ? full((rows - k) % rows, ml) : 0.0);
        }
    }
    return out;
}

double WienerFilter::gain() const { return g_.size() == 0 ? 0.0 : std::sqrt(g_.abs2().maxCoeff()); }

}  // namespace pinmask
