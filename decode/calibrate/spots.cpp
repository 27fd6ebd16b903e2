#include "decode/calibrate/spots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/errors/error.hpp"

namespace pinmask::calibrate {

double median_of(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    double m = *mid;
    if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), mid));
    return m;
}

Background estimate_background(const Plane& image) {
    if (image.size() == 0) throw InvalidInput("calibrate: the capture is empty");
    if (!is_all_finite(image)) throw InvalidInput("calibrate: the capture holds NaN or Inf");
    std::vector<double> v(image.data(), image.data() + image.size());
    Background b;
    b.level = median_of(v);
    for (double& x : v) x = std::abs(x - b.level);
    b.sigma = 1.4826 * median_of(std::move(v));  // MAD -> Gaussian sigma
    return b;
}

namespace {

// Connected components above `threshold` (see detect_spots); `peaks` gets each one's largest
// smoothed value.
std::vector<Spot> components(const Plane& image, const Plane& smooth, double threshold,
                             std::vector<std::uint8_t>& seen, const SpotOptions& options,
                             const Background& bg, const Plane& raw, std::vector<double>& peaks) {
    const int rows = static_cast<int>(image.rows()), cols = static_cast<int>(image.cols());
    std::vector<Spot> spots;
    std::vector<int> stack;
    for (int r0 = 0; r0 < rows; ++r0) {
        for (int c0 = 0; c0 < cols; ++c0) {
            const std::size_t i0 = static_cast<std::size_t>(r0) * cols + c0;
            if (seen[i0] || smooth(r0, c0) <= threshold) continue;
            Spot s;
            s.row0 = s.row1 = r0;
            s.col0 = s.col1 = c0;
            stack.assign(1, static_cast<int>(i0));
            seen[i0] = 1;
            while (!stack.empty()) {
                const int i = stack.back();
                stack.pop_back();
                const int r = i / cols, c = i % cols;
                ++s.area_px;
                s.row0 = std::min(s.row0, r);
                s.row1 = std::max(s.row1, r);
                s.col0 = std::min(s.col0, c);
                s.col1 = std::max(s.col1, c);
                for (int dr = -1; dr <= 1; ++dr)
                    for (int dc = -1; dc <= 1; ++dc) {
                        const int rr = r + dr, cc = c + dc;
                        if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                        const std::size_t j = static_cast<std::size_t>(rr) * cols + cc;
                        if (seen[j] || smooth(rr, cc) <= threshold) continue;
                        seen[j] = 1;
                        stack.push_back(static_cast<int>(j));
                    }
            }
            if (s.area_px < options.min_area_px) continue;
            double smooth_peak = -1e300;
            for (int r = s.row0; r <= s.row1; ++r)
                for (int c = s.col0; c <= s.col1; ++c)
                    smooth_peak = std::max(smooth_peak, smooth(r, c));
            peaks.push_back(smooth_peak);
            double sw = 0.0, sx = 0.0, sy = 0.0;
            const int ra = std::max(0, s.row0 - 1), rb = std::min(rows - 1, s.row1 + 1);
            const int ca = std::max(0, s.col0 - 1), cb = std::min(cols - 1, s.col1 + 1);
            for (int r = ra; r <= rb; ++r)
                for (int c = ca; c <= cb; ++c) {
                    const double v = image(r, c);
                    s.peak = std::max(s.peak, v);
                    if (raw(r, c) >= options.saturation_level) s.saturated = true;
                    const double w = v - bg.level;
                    sw += w;
                    sx += w * c;
                    sy += w * r;
                }
            if (!(sw > 0.0)) continue;
            s.flux = sw;
            s.x = sx / sw;
            s.y = sy / sw;
            spots.push_back(s);
        }
    }
    return spots;
}

}  // namespace

std::vector<Spot> detect_spots(const Plane& image, const Background& bg,
                               const SpotOptions& options) {
    const int rows = static_cast<int>(image.rows()), cols = static_cast<int>(image.cols());
    // 3 x 3 box mean (edges: mean of the pixels inside the frame).
    Plane smooth(rows, cols);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            double s = 0.0;
            int n = 0;
            for (int dr = -1; dr <= 1; ++dr)
                for (int dc = -1; dc <= 1; ++dc) {
                    const int rr = r + dr, cc = c + dc;
                    if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                    s += image(rr, cc);
                    ++n;
                }
            smooth(r, c) = s / n;
        }
    }
    // A flat frame (sigma 0) still needs a threshold above rounding: a tiny fraction of the
    // background's magnitude, at least one count of 2^-20.
    const double sigma = std::max(bg.sigma, 1e-6 * std::max(std::abs(bg.level), 1.0));
    const double noise_threshold = bg.level + options.threshold_sigmas * sigma / 3.0;
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(rows) * cols, 0);
    const Plane& raw = options.raw ? *options.raw : image;
    double threshold = noise_threshold;
    for (int pass = 0; pass < 2; ++pass) {
        std::fill(seen.begin(), seen.end(), 0);
        std::vector<double> peaks;
        const auto spots = components(image, smooth, threshold, seen, options, bg, raw, peaks);
        if (pass == 1 || peaks.empty()) return spots;
        const double relative =
            bg.level + options.relative_threshold * (median_of(peaks) - bg.level);
        if (relative <= threshold) return spots;
        threshold = relative;
    }
    return {};
}

}  // namespace pinmask::calibrate
