#include "decode/capture/capture_defaults.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "decode/solvers/noise_estimate.hpp"

namespace pinmask {
namespace {

// The q quantile of the values (the element at floor(q (n - 1)), no interpolation).
double quantile(const Plane& p, double q) {
    std::vector<double> v(p.data(), p.data() + p.size());
    if (v.empty()) return 0.0;
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<std::size_t>(k)];
}

}  // namespace

bool psf_covers_capture(int capture_rows, int capture_cols, int psf_rows, int psf_cols) {
    return psf_rows >= capture_rows && psf_cols >= capture_cols;
}

double psf_floor(const Plane& psf) { return std::max(0.0, quantile(psf, kPsfFloorQuantile)); }

bool whole_numbers(const Plane& p) {
    for (Eigen::Index i = 0; i < p.size(); ++i)
        if (p.data()[i] != std::floor(p.data()[i])) return false;
    return true;
}

bool whole_numbers(const Image& image) {
    for (const Plane& p : image.channels)
        if (!whole_numbers(p)) return false;
    return true;
}

bool capture_is_intensity(const Image& capture, double& low, double& sigma) {
    low = INFINITY;
    sigma = 0.0;
    for (const Plane& p : capture.channels) {
        low = std::min(low, quantile(p, 0.001));
        sigma = std::max(sigma, estimate_noise_sigma(p));
    }
    return low >= -3.0 * sigma;
}

double border_fill(const Plane& capture) {
    const Eigen::Index rows = capture.rows(), cols = capture.cols();
    const Eigen::Index b = std::max<Eigen::Index>(1, std::min(rows, cols) / kBorderBandDivisor);
    if (2 * b >= rows || 2 * b >= cols) return 0.0;
    const double all = capture.abs().sum();
    const double inner = capture.block(b, b, rows - 2 * b, cols - 2 * b).abs().sum();
    const double border_pixels = static_cast<double>(rows * cols - (rows - 2 * b) * (cols - 2 * b));
    const double mean = all / static_cast<double>(rows * cols);
    if (!(mean > 0.0)) return 0.0;
    return (all - inner) / border_pixels / mean;
}

double border_fill(const Image& capture) {
    double fill = 0.0;
    for (const Plane& p : capture.channels) fill = std::max(fill, border_fill(p));
    return fill;
}

bool auto_method_is_tv(bool linear_model) { return linear_model; }

}  // namespace pinmask
