#include "decode/solvers/auto_weight.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/noise_estimate.hpp"

namespace pinmask {
namespace {

constexpr int kBands = 12;
// k of the TV rule (auto_weight.hpp): the gain of least worst-case PSNR loss against each case's
// best gain on the low-light training set of scripts/autoreg_table.py --calibrate-tv (24 cases;
// gains 10^(i/8): 2.37 loses at most 0.79 dB, 0.23 dB on average; 1.78: 1.77 and 0.19 dB).
constexpr double kTvLambdaPerNoise = 2.4;
// Above a capture SNR (mean / sigma) of kTvSnrKnee the best gain falls as SNR^-kTvSnrExponent
// (the same training cameras at 1e2..1e6 electrons per unit: best gains 1.3-3.2 at SNR 7,
// 0.3-0.6 at SNR 200-600; --calibrate-tv fits the fall). The knee keeps k where it was
// calibrated (SNR 7-22).
constexpr double kTvSnrKnee = 16.0;
constexpr double kTvSnrExponent = 2.0 / 3.0;
constexpr double kAlphaMax = 4.0;

// Radial frequency |f| (cycles per pixel) of half-spectrum entry (k, l).
double radius(int k, int l, int rows, int cols) {
    const double fy = (k <= rows / 2 ? k : k - rows) / static_cast<double>(rows);
    const double fx = l / static_cast<double>(cols);
    return std::sqrt(fy * fy + fx * fx);
}

// 1 for columns that are their own Hermitian partner's (0 and, for even cols, cols / 2), else 2.
double multiplicity(int l, int cols) { return l == 0 || (cols % 2 == 0 && l == cols / 2) ? 1 : 2; }

// The fitted scene power S on the half spectrum (see auto_weight.hpp) and its exponent.
Plane fit_scene_power(const ComplexPlane& spectrum, const ComplexPlane& otf, double n,
                      double noise_power, int rows, int cols, double& alpha) {
    const int hc = cols / 2 + 1;
    const double f_lo = 0.999 / std::max(rows, cols), f_hi = 0.75;
    std::vector<double> num(kBands, 0.0), cnt(kBands, 0.0), den(kBands, 0.0);
    for (int k = 0; k < rows; ++k) {
        for (int l = 0; l < hc; ++l) {
            const double f = radius(k, l, rows, cols);
            if (f < f_lo) continue;
            const int b = std::min(
                kBands - 1, static_cast<int>(kBands * std::log(f / f_lo) / std::log(f_hi / f_lo)));
            const double m = multiplicity(l, cols);
            num[b] += m * (std::norm(spectrum(k, l)) / n - noise_power);
            cnt[b] += m;
            den[b] += m * std::norm(otf(k, l));
        }
    }
    // Weighted least squares of log S_band = log c - alpha log f_band, weights the band's count.
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    std::vector<double> xs, ys, ws;
    for (int b = 0; b < kBands; ++b) {
        if (!(num[b] > noise_power * cnt[b]) || !(den[b] > 0.0)) continue;
        const double fb = f_lo * std::pow(f_hi / f_lo, (b + 0.5) / kBands);
        const double x = std::log(fb), y = std::log(num[b] / den[b]), w = cnt[b];
        xs.push_back(x);
        ys.push_back(y);
        ws.push_back(w);
        sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
    }
    alpha = 0.0;
    double log_c = -INFINITY;  // no band above the noise: no scene power beyond the mean
    if (!xs.empty()) {
        const double var = sxx - sx * sx / sw;
        if (xs.size() >= 2 && var > 0.0) alpha = -(sxy - sx * sy / sw) / var;
        alpha = std::clamp(alpha, 0.0, kAlphaMax);
        log_c = (sy + alpha * sx) / sw;  // the intercept refitted for the clamped exponent
    }
    Plane s(rows, hc);
    for (int k = 0; k < rows; ++k) {
        for (int l = 0; l < hc; ++l) {
            const double f = radius(k, l, rows, cols);
            s(k, l) = f > 0.0 && std::isfinite(log_c) ? std::exp(log_c - alpha * std::log(f)) : 0.0;
        }
    }
    // The mean is measured, not modelled (its SNR is the highest of all frequencies).
    const double h0 = std::norm(otf(0, 0));
    s(0, 0) = h0 > 0.0 ? std::max(std::norm(spectrum(0, 0)) / n - noise_power, 0.0) / h0 : 0.0;
    return s;
}

// Mean square of the band of width max(1, min(rows, cols) / 16) along the edges (the whole
// plane when the band would cover it).
double border_mean_square(const Plane& p) {
    const Eigen::Index rows = p.rows(), cols = p.cols();
    const Eigen::Index b = std::max<Eigen::Index>(1, std::min(rows, cols) / 16);
    const double all = p.square().sum();
    if (2 * b >= rows || 2 * b >= cols) return all / static_cast<double>(p.size());
    const double inner = p.block(b, b, rows - 2 * b, cols - 2 * b).square().sum();
    return (all - inner) / static_cast<double>(rows * cols - (rows - 2 * b) * (cols - 2 * b));
}

}  // namespace

double closed_form_risk(const ComplexPlane& otf, const Plane& symbol, const Plane& scene_power,
                        double noise_power, int cols, double weight) {
    double risk = 0.0;
    for (Eigen::Index k = 0; k < otf.rows(); ++k) {
        for (Eigen::Index l = 0; l < otf.cols(); ++l) {
            const double h2 = std::norm(otf(k, l)), wl = weight * symbol(k, l);
            const double d = h2 + wl;
            // The filter is 0 where the denominator is: the error is the scene's power there.
            const double e = d > 0.0 ? (wl * wl * scene_power(k, l) + h2 * noise_power) / (d * d)
                                     : scene_power(k, l);
            risk += multiplicity(static_cast<int>(l), cols) * e;
        }
    }
    return risk;
}

AutoWeight choose_closed_form_weight(const Plane& capture, const ComplexPlane& otf,
                                     const Plane& symbol, int rows, int cols,
                                     std::optional<double> noise_sigma) {
    const int hc = cols / 2 + 1;
    if (otf.rows() != rows || otf.cols() != hc || symbol.rows() != rows || symbol.cols() != hc ||
        capture.rows() > rows || capture.cols() > cols || capture.size() == 0) {
        throw InvalidInput("choose_closed_form_weight: capture, otf and symbol must fit the " +
                           std::to_string(rows) + " x " + std::to_string(cols) + " working grid");
    }
    // Work on capture / 2^e (exact), so any magnitude meets the same numbers.
    const double peak = capture.abs().maxCoeff();
    int e = 0;
    if (peak > 0.0) std::frexp(peak, &e);
    const double scale = std::ldexp(1.0, e);
    Plane padded = Plane::Zero(rows, cols);
    padded.topLeftCorner(capture.rows(), capture.cols()) = capture / scale;
    AutoWeight out;
    const double sigma =
        noise_sigma ? *noise_sigma / scale
                    : estimate_noise_sigma(padded.topLeftCorner(capture.rows(), capture.cols()));
    out.noise_sigma = sigma * scale;
    const double n = static_cast<double>(rows) * cols;
    const double n_capture = static_cast<double>(capture.size());
    const double noise_power =
        (sigma * sigma * n_capture + border_mean_square(capture / scale) * (n - n_capture)) / n;
    const ComplexPlane spectrum = Fft2(rows, cols).forward(padded);
    const Plane s = fit_scene_power(spectrum, otf, n, noise_power, rows, cols, out.alpha);

    const double h2max = otf.abs2().maxCoeff();
    if (!(h2max > 0.0)) {
        out.weight = 0.0;
        return out;
    }
    const auto risk = [&](double log_w) {
        return closed_form_risk(otf, symbol, s, noise_power, cols, h2max * std::exp(log_w));
    };
    const double lo = std::log(1e-10), hi = std::log(1e2), step = std::log(10.0) / 4;
    const int points = static_cast<int>(std::lround((hi - lo) / step)) + 1;
    int best = 0;
    double best_risk = INFINITY;
    for (int i = 0; i < points; ++i) {
        const double r = risk(lo + i * step);
        if (r < best_risk) best_risk = r, best = i;  // the first (smallest weight) of ties
    }
    double a = lo + std::max(best - 1, 0) * step, b = lo + std::min(best + 1, points - 1) * step;
    const double g = (std::sqrt(5.0) - 1) / 2;
    double c = b - g * (b - a), d = a + g * (b - a);
    double rc = risk(c), rd = risk(d);
    for (int i = 0; i < 40; ++i) {
        if (rc <= rd) {
            b = d, d = c, rd = rc;
            c = b - g * (b - a);
            rc = risk(c);
        } else {
            a = c, c = d, rc = rd;
            d = a + g * (b - a);
            rd = risk(d);
        }
    }
    double log_w = (a + b) / 2;
    if (best_risk < risk(log_w)) log_w = lo + best * step;  // a grid end point, kept exactly
    out.weight = h2max * std::exp(log_w);
    return out;
}

AutoWeight choose_tv_weight(const Plane& capture, const Plane& psf,
                            std::optional<double> noise_sigma) {
    AutoWeight out;
    out.noise_sigma = noise_sigma ? *noise_sigma : estimate_noise_sigma(capture);
    out.weight = kTvLambdaPerNoise * out.noise_sigma * std::sqrt(psf.square().sum());
    // A signed capture (mean <= 0) or one without measurable noise keeps the low-SNR gain.
    const double snr = out.noise_sigma > 0.0 ? capture.mean() / out.noise_sigma : 0.0;
    if (snr > kTvSnrKnee) out.weight *= std::pow(kTvSnrKnee / snr, kTvSnrExponent);
    return out;
}

}  // namespace pinmask
