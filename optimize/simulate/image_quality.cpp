#include "optimize/simulate/image_quality.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

std::string size_text(const Plane& p) {
    return std::to_string(p.rows()) + " x " + std::to_string(p.cols());
}

void check_same(const Plane& x, const Plane& ref) {
    if (x.rows() != ref.rows() || x.cols() != ref.cols()) {
        throw InvalidInput("image quality: image is " + size_text(x) + ", reference is " +
                           size_text(ref) + ": sizes must match");
    }
    if (x.size() == 0) throw InvalidInput("image quality: empty image");
}

void check_same(const Image& x, const Image& ref) {
    if (x.n_channels() != ref.n_channels() || x.n_channels() == 0) {
        throw InvalidInput("image quality: image has " + std::to_string(x.n_channels()) +
                           " channels, reference " + std::to_string(ref.n_channels()) +
                           ": counts must match and be >= 1");
    }
}

// Normalised 1-D Gaussian of kSsimWindow taps; the 2-D window is its outer product.
std::array<double, kSsimWindow> gaussian_taps() {
    std::array<double, kSsimWindow> g{};
    double sum = 0.0;
    for (int i = 0; i < kSsimWindow; ++i) {
        const double t = i - kSsimWindow / 2;
        g[i] = std::exp(-t * t / (2.0 * kSsimSigma * kSsimSigma));
        sum += g[i];
    }
    for (double& v : g) v /= sum;
    return g;
}

// "Valid" separable filtering with the Gaussian window: (R - 10) x (C - 10).
Plane filter_valid(const Plane& in, const std::array<double, kSsimWindow>& g) {
    const Eigen::Index R = in.rows(), C = in.cols(), W = kSsimWindow;
    Plane tmp = Plane::Zero(R, C - W + 1);
    for (Eigen::Index r = 0; r < R; ++r)
        for (Eigen::Index c = 0; c + W <= C; ++c) {
            double s = 0.0;
            for (Eigen::Index k = 0; k < W; ++k) s += g[k] * in(r, c + k);
            tmp(r, c) = s;
        }
    Plane out = Plane::Zero(R - W + 1, C - W + 1);
    for (Eigen::Index r = 0; r + W <= R; ++r)
        for (Eigen::Index k = 0; k < W; ++k) out.row(r) += g[k] * tmp.row(r + k);
    return out;
}

}  // namespace

double mse(const Plane& x, const Plane& ref) {
    check_same(x, ref);
    return (x - ref).square().mean();
}

double psnr_from_mse(double m) {
    if (!(m >= 0.0)) throw invalid_field("mse", std::to_string(m), "must be >= 0");
    if (m == 0.0) return std::numeric_limits<double>::infinity();
    return -10.0 * std::log10(m);
}

double psnr_db(const Plane& x, const Plane& ref) { return psnr_from_mse(mse(x, ref)); }

Plane ssim_map(const Plane& x, const Plane& ref) {
    check_same(x, ref);
    if (x.rows() < kSsimWindow || x.cols() < kSsimWindow) {
        throw InvalidInput("SSIM: image is " + size_text(x) + ": both sides must be >= " +
                           std::to_string(kSsimWindow) + " (the Gaussian window)");
    }
    const auto g = gaussian_taps();
    const Plane mx = filter_valid(x, g), my = filter_valid(ref, g);
    const Plane sxx = filter_valid(x * x, g) - mx * mx;
    const Plane syy = filter_valid(ref * ref, g) - my * my;
    const Plane sxy = filter_valid(x * ref, g) - mx * my;
    const double c1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0), c2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0);
    return ((2.0 * mx * my + c1) * (2.0 * sxy + c2)) /
           ((mx * mx + my * my + c1) * (sxx + syy + c2));
}

double ssim(const Plane& x, const Plane& ref) { return ssim_map(x, ref).mean(); }

double mse(const Image& x, const Image& ref) {
    check_same(x, ref);
    double s = 0.0;
    for (int c = 0; c < x.n_channels(); ++c) s += mse(x.channels[c], ref.channels[c]);
    return s / x.n_channels();
}

double psnr_db(const Image& x, const Image& ref) { return psnr_from_mse(mse(x, ref)); }

double ssim(const Image& x, const Image& ref) {
    check_same(x, ref);
    double s = 0.0;
    for (int c = 0; c < x.n_channels(); ++c) s += ssim(x.channels[c], ref.channels[c]);
    return s / x.n_channels();
}

}  // namespace pinmask
