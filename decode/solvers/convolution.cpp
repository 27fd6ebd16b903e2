#include "decode/solvers/convolution.hpp"

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "decode/solvers/psf2otf.hpp"

namespace pinmask {
namespace {

std::string size_text(Eigen::Index r, Eigen::Index c) {
    return std::to_string(r) + " x " + std::to_string(c);
}

// Working planes a solver may hold at once (x, duals, splits, spectra), for the memory bound.
constexpr double kPlanesPerSolve = 24.0;

}  // namespace

int next_fft_size(int n) {
    if (n < 1) throw invalid_field("fft size", std::to_string(n), "must be >= 1");
    for (int m = n;; ++m) {
        int k = m;
        for (int f : {2, 3, 5, 7}) {
            while (k % f == 0) k /= f;
        }
        if (k == 1) return m;
    }
}

ConvGeometry make_conv_geometry(ConvModel model, int capture_rows, int capture_cols, int psf_rows,
                                int psf_cols) {
    if (capture_rows < 1 || capture_cols < 1) {
        throw invalid_field("capture", size_text(capture_rows, capture_cols), "must not be empty");
    }
    if (psf_rows < 1 || psf_cols < 1) {
        throw invalid_field("psf", size_text(psf_rows, psf_cols), "must not be empty");
    }
    ConvGeometry g;
    g.model = model;
    g.capture_rows = capture_rows;
    g.capture_cols = capture_cols;
    if (model == ConvModel::kCyclic) {
        if (psf_rows > capture_rows || psf_cols > capture_cols) {
            throw invalid_field("psf", size_text(psf_rows, psf_cols),
                                "must not be larger than the capture (working size " +
                                    size_text(capture_rows, capture_cols) +
                                    ") for the cyclic model; crop one period or use the linear "
                                    "model");
        }
        g.work_rows = capture_rows;
        g.work_cols = capture_cols;
    } else {
        g.work_rows = next_fft_size(capture_rows + psf_rows - 1);
        g.work_cols = next_fft_size(capture_cols + psf_cols - 1);
        g.crop_row = (g.work_rows - capture_rows) / 2;
        g.crop_col = (g.work_cols - capture_cols) / 2;
    }
    check_memory(kPlanesPerSolve * 8.0 * g.work_rows * static_cast<double>(g.work_cols),
                 "decoding on a " + size_text(g.work_rows, g.work_cols) + " grid");
    return g;
}

Plane crop_to_capture(const ConvGeometry& g, const Plane& work) {
    if (work.rows() != g.work_rows || work.cols() != g.work_cols) {
        throw invalid_field("working plane", size_text(work.rows(), work.cols()),
                            "must be " + size_text(g.work_rows, g.work_cols));
    }
    return work.block(g.crop_row, g.crop_col, g.capture_rows, g.capture_cols);
}

Plane pad_to_work(const ConvGeometry& g, const Plane& capture) {
    if (capture.rows() != g.capture_rows || capture.cols() != g.capture_cols) {
        throw invalid_field("capture", size_text(capture.rows(), capture.cols()),
                            "must be " + size_text(g.capture_rows, g.capture_cols));
    }
    if (g.work_rows == g.capture_rows && g.work_cols == g.capture_cols) return capture;
    Plane out = Plane::Zero(g.work_rows, g.work_cols);
    out.block(g.crop_row, g.crop_col, g.capture_rows, g.capture_cols) = capture;
    return out;
}

ConvolutionOperator::ConvolutionOperator(const Plane& psf, const ConvGeometry& geometry)
    : geometry_(geometry),
      fft_(geometry.work_rows, geometry.work_cols),
      otf_(psf2otf(psf, geometry.work_rows, geometry.work_cols)),
      // max |H| as the root of max |H|^2 (|z| of a complex calls hypot per value: 10 % of a
      // warm 128 x 128 Wiener decode).
      otf_max_abs_(std::sqrt(otf_.abs2().maxCoeff())) {}

Plane ConvolutionOperator::convolve(const Plane& x) const {
    return fft_.inverse(fft_.forward(x) * otf_);
}

Plane ConvolutionOperator::correlate(const Plane& v) const {
    return fft_.inverse(fft_.forward(v) * otf_.conjugate());
}

Plane ConvolutionOperator::apply(const Plane& x) const {
    return crop_to_capture(geometry_, convolve(x));
}

Plane ConvolutionOperator::adjoint(const Plane& y) const {
    return correlate(pad_to_work(geometry_, y));
}

}  // namespace pinmask
