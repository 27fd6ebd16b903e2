#include "decode/solvers/wiener.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/precision.hpp"
#include "decode/solvers/psf2otf.hpp"

namespace pinmask {
namespace {

void check_floor(double floor) {
    if (!(floor >= 0.0) || !std::isfinite(floor)) {
        throw invalid_field("denominator_floor", std::to_string(floor), "must be finite and >= 0");
    }
}

// conj(h) / max(|h|^2 + nsr, floor), 0 where that denominator is 0. Written in real parts (the
// operations of std::norm and complex / real, so the same bits) so that its loops vectorise.
std::complex<double> wiener_gain(std::complex<double> h, double nsr, double floor) {
    const double re = h.real(), im = h.imag();
    const double denom = std::max(re * re + im * im + nsr, floor);
    return denom > 0.0 ? std::complex<double>(re / denom, -im / denom)
                       : std::complex<double>(0.0, 0.0);
}

void check_otf(const ComplexPlane& otf, int rows, int cols) {
    if (rows < 1 || cols < 1 || otf.rows() != rows || otf.cols() != cols / 2 + 1) {
        throw invalid_field(
            "otf", std::to_string(otf.rows()) + " x " + std::to_string(otf.cols()),
            "must be the half spectrum of " + std::to_string(rows) + " x " + std::to_string(cols));
    }
}

// Sums over the half-spectrum entries [i0, i1) of one multiplicity class, with the filter applied
// on the way (spectrum <- g_scaled .* spectrum): |H X - P|^2, |X|^2 and weight |X|^2 for the
// unscaled estimate spectrum X = N g_scaled P, in double. Real arithmetic written out: the
// complex operators' NaN/Inf recovery paths (C99 Annex G) keep a loop from vectorising.
struct RangeSums {
    double res2 = 0.0, x2 = 0.0, weighted = 0.0;
};

template <class T, bool kOtf, bool kWeight>
RangeSums filter_range(std::complex<T>* spectrum, const std::complex<T>* g_scaled,
                       const std::complex<double>* H, const double* w, Eigen::Index i0,
                       Eigen::Index i1, double n) {
    T* sp = reinterpret_cast<T*>(spectrum);  // [re, im] pairs, as std::complex guarantees
    const T* g = reinterpret_cast<const T*>(g_scaled);
    const double* h = reinterpret_cast<const double*>(H);
    double res2 = 0.0, x2 = 0.0, weighted = 0.0;
    // The sums' order is the vector width's (fixed for a build: same bits run to run).
#pragma omp simd reduction(+ : res2, x2, weighted)
    for (Eigen::Index i = i0; i < i1; ++i) {
        const T pr = sp[2 * i], pi = sp[2 * i + 1];
        const T gr = g[2 * i], gi = g[2 * i + 1];
        const T xr = gr * pr - gi * pi, xi = gr * pi + gi * pr;
        sp[2 * i] = xr;
        sp[2 * i + 1] = xi;
        const double dxr = static_cast<double>(xr) * n, dxi = static_cast<double>(xi) * n;
        const double e = dxr * dxr + dxi * dxi;
        x2 += e;
        if constexpr (kOtf) {
            const double hr = h[2 * i], hi = h[2 * i + 1];
            const double rr = hr * dxr - hi * dxi - static_cast<double>(pr);
            const double ri = hr * dxi + hi * dxr - static_cast<double>(pi);
            res2 += rr * rr + ri * ri;
        }
        if constexpr (kWeight) weighted += w[i] * e;
    }
    return {res2, x2, weighted};
}

// spectrum <- g_scaled .* spectrum (g_scaled = G / N), gathering the requested sums of
// SpectralSums over the unscaled estimate spectrum X = N g_scaled P, in double. Each row's
// columns 0 and (even cols) cols / 2 count once, the others twice (their Hermitian partners).
template <class T, bool kOtf, bool kWeight>
void filter_rows(std::complex<T>* spectrum, const std::complex<T>* g_scaled,
                 const std::complex<double>* H, const double* w, int rows, int cols,
                 SpectralSums& sums) {
    const double n = static_cast<double>(rows) * cols;
    const Eigen::Index hc = cols / 2 + 1;
    const Eigen::Index last = cols % 2 == 0 ? hc - 1 : hc;  // interior columns [1, last)
    RangeSums once, twice;
    const auto add = [](RangeSums& a, const RangeSums& b) {
        a.res2 += b.res2;
        a.x2 += b.x2;
        a.weighted += b.weighted;
    };
    for (Eigen::Index k = 0; k < rows; ++k) {
        const Eigen::Index b = k * hc;
        add(once, filter_range<T, kOtf, kWeight>(spectrum, g_scaled, H, w, b, b + 1, n));
        if (last > 1)
            add(twice,
                filter_range<T, kOtf, kWeight>(spectrum, g_scaled, H, w, b + 1, b + last, n));
        if (last < hc)
            add(once,
                filter_range<T, kOtf, kWeight>(spectrum, g_scaled, H, w, b + last, b + hc, n));
    }
    sums.residual2 = kOtf ? (once.res2 + 2.0 * twice.res2) / n : 0.0;
    // A weight plane already counts the partners (half_spectrum_multiplicity); a uniform one not.
    sums.penalty = kWeight               ? (once.weighted + twice.weighted) / n
                   : sums.uniform_weight ? *sums.uniform_weight * (once.x2 + 2.0 * twice.x2) / n
                                         : 0.0;
}

template <class T>
void filter_with_sums(
    Eigen::Array<std::complex<T>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& spectrum,
    const Eigen::Array<std::complex<T>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& g_scaled,
    int rows, int cols, SpectralSums& sums) {
    const int hc = cols / 2 + 1;
    const ComplexPlane* H = sums.otf;
    const Plane* w = sums.weight;
    if (H) check_otf(*H, rows, cols);
    if (w && (w->rows() != rows || w->cols() != hc)) {
        throw invalid_field(
            "weight", std::to_string(w->rows()) + " x " + std::to_string(w->cols()),
            "must be the half spectrum of " + std::to_string(rows) + " x " + std::to_string(cols));
    }
    if (w && sums.uniform_weight)
        throw invalid_field("uniform_weight", "set", "excludes a weight plane");
    std::complex<T>* sp = spectrum.data();
    const std::complex<T>* g = g_scaled.data();
    const std::complex<double>* h = H ? H->data() : nullptr;
    const double* wd = w ? w->data() : nullptr;
    if (H && w)
        filter_rows<T, true, true>(sp, g, h, wd, rows, cols, sums);
    else if (H)
        filter_rows<T, true, false>(sp, g, h, wd, rows, cols, sums);
    else if (w)
        filter_rows<T, false, true>(sp, g, h, wd, rows, cols, sums);
    else
        filter_rows<T, false, false>(sp, g, h, wd, rows, cols, sums);
}

void check_scale(double scale) {
    if (!(scale > 0.0) || !std::isfinite(scale))
        throw invalid_field("scale", std::to_string(scale), "must be finite and > 0");
}

}  // namespace

WienerFilter::WienerFilter(int rows, int cols, ComplexPlane g)
    : rows_(rows), cols_(cols), fft_(rows, cols), g_(std::move(g)) {
    finish();
}

void WienerFilter::finish() {
    const double inv_n = 1.0 / (static_cast<double>(rows_) * cols_);
    // The float copy only where --precision auto decodes in float (kSinglePrecisionMinPixels):
    // below it apply_single converts into its workspace per call (a warm 128 x 128 Wiener
    // decode spent 5 % making a copy it never used). Both copies in one pass over g_.
    g_scaled_.resize(g_.rows(), g_.cols());
    const bool with_float = static_cast<long long>(rows_) * cols_ >= kSinglePrecisionMinPixels;
    if (with_float) g_scaled_f_.resize(g_.rows(), g_.cols());
    const std::complex<double>* g = g_.data();
    std::complex<double>* gs = g_scaled_.data();
    std::complex<float>* gf = with_float ? g_scaled_f_.data() : nullptr;
    for (Eigen::Index i = 0; i < g_.size(); ++i) {
        gs[i] = std::complex<double>(g[i].real() * inv_n, g[i].imag() * inv_n);
        if (gf) gf[i] = std::complex<float>(gs[i]);
    }
}

WienerFilter WienerFilter::from_otf(const ComplexPlane& otf, int rows, int cols, double nsr,
                                    double denominator_floor) {
    if (!(nsr >= 0.0) || !std::isfinite(nsr)) {
        throw invalid_field("nsr", std::to_string(nsr), "must be finite and >= 0");
    }
    check_floor(denominator_floor);
    check_otf(otf, rows, cols);
    ComplexPlane g(otf.rows(), otf.cols());
    const std::complex<double>* h = otf.data();
    std::complex<double>* gd = g.data();
    for (Eigen::Index i = 0; i < otf.size(); ++i) gd[i] = wiener_gain(h[i], nsr, denominator_floor);
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

void WienerFilter::apply(const Plane& capture, Plane& out, Workspace& ws, SpectralSums* sums,
                         double scale) const {
    check_capture(capture);
    check_scale(scale);
    if (scale != 1.0) ws.scaled = capture * (1.0 / scale);  // exact: a power of two
    fft_.forward(scale != 1.0 ? ws.scaled : capture, ws.spectrum);
    if (sums) {
        filter_with_sums(ws.spectrum, g_scaled_, rows_, cols_, *sums);
    } else {
        ws.spectrum *= g_scaled_;  // with the 1/N of the inverse transform
    }
    fft_.inverse_unscaled_destroy(ws.spectrum, out);
    if (scale != 1.0) out *= scale;
}

void WienerFilter::apply_single(const Plane& capture, Plane& out, WorkspaceF& ws,
                                SpectralSums* sums, double scale) const {
    check_capture(capture);
    check_scale(scale);
    const Fft2f fft(rows_, cols_);
    if (scale != 1.0) {
        ws.in = (capture * (1.0 / scale)).cast<float>();  // exact: a power of two
    } else {
        ws.in = capture.cast<float>();
    }
    fft.forward(ws.in, ws.spectrum);
    if (g_scaled_f_.size() == 0) ws.filter = g_scaled_.cast<std::complex<float>>();
    const ComplexPlaneF& g = g_scaled_f_.size() == 0 ? ws.filter : g_scaled_f_;
    if (sums) {
        filter_with_sums(ws.spectrum, g, rows_, cols_, *sums);
    } else {
        ws.spectrum *= g;
    }
    fft.inverse_unscaled_destroy(ws.spectrum, ws.out);
    if (scale != 1.0) {
        out = ws.out.cast<double>() * scale;
    } else {
        out = ws.out.cast<double>();
    }
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
