// File scenes and the exact area-average resampler.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {
namespace {

// Values above 1 by at most this after dividing by the full scale are rounding, clamped to 1.
constexpr double kFullScaleSlack = 1e-12;

// For each output index, the (input index, weight) pairs: weight = overlap of the input pixel
// [i, i+1) with the output footprint [o in/out, (o+1) in/out), divided by the footprint length.
std::vector<std::vector<std::pair<int, double>>> area_weights(int in, int out) {
    std::vector<std::vector<std::pair<int, double>>> w(static_cast<std::size_t>(out));
    const double step = static_cast<double>(in) / out;
    for (int o = 0; o < out; ++o) {
        const double a = o * step, b = (o + 1 == out) ? in : (o + 1) * step;
        const int i0 = static_cast<int>(std::floor(a));
        const int i1 = std::min(in - 1, static_cast<int>(std::ceil(b)) - 1);
        for (int i = std::max(0, i0); i <= i1; ++i) {
            const double ov = std::min(b, i + 1.0) - std::max(a, static_cast<double>(i));
            if (ov > 0.0) w[o].emplace_back(i, ov / (b - a));
        }
    }
    return w;
}

}  // namespace

Plane resample_area(const Plane& in, int rows, int cols) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput("resample size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
    if (in.size() == 0) throw InvalidInput("resample: empty input image");
    const int H = static_cast<int>(in.rows()), W = static_cast<int>(in.cols());
    if (H == rows && W == cols) return in;
    const auto wr = area_weights(H, rows), wc = area_weights(W, cols);
    Plane tmp = Plane::Zero(H, cols);  // columns first
    for (int c = 0; c < cols; ++c)
        for (const auto& [i, w] : wc[c]) tmp.col(c) += w * in.col(i);
    Plane out = Plane::Zero(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (const auto& [i, w] : wr[r]) out.row(r) += w * tmp.row(i);
    return out;
}

Image file_scene(const std::filesystem::path& path, int rows, int cols) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput("scene size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
    LoadedImage loaded = read_image(path);
    const int channels = loaded.image.n_channels();
    if (channels != 1 && channels != 3) {
        throw InvalidInput("scene file " + path.string() + ": " + std::to_string(channels) +
                           " channels: must be 1 (grey) or 3 (RGB)");
    }
    Image out;
    for (Plane& plane : loaded.image.channels) {
        plane /= loaded.full_scale;
        for (Eigen::Index r = 0; r < plane.rows(); ++r)
            for (Eigen::Index c = 0; c < plane.cols(); ++c) {
                const double v = plane(r, c);
                if (!(v >= 0.0 && v <= 1.0 + kFullScaleSlack)) {
                    std::ostringstream s;
                    s << "scene file " << path.string() << ": value " << v << " at (row " << r
                      << ", col " << c << ") after dividing by the full scale " << loaded.full_scale
                      << ": must be in [0, 1]";
                    throw InvalidInput(s.str());
                }
            }
        out.channels.push_back(resample_area(plane.min(1.0), rows, cols));
    }
    return out;
}

}  // namespace pinmask
