#include "decode/depthmap/depthmap_picture.hpp"

#include <algorithm>
#include <cmath>

namespace pinmask {

namespace {

// A blue-to-yellow ramp (dark near, bright far) for t in [0, 1].
void ramp(double t, double& r, double& g, double& b) {
    t = std::clamp(t, 0.0, 1.0);
    r = std::clamp(1.5 * t - 0.25, 0.0, 1.0);
    g = std::clamp(0.15 + 0.8 * t, 0.0, 1.0);
    b = std::clamp(0.55 + 0.5 * t - 1.0 * t * t, 0.0, 1.0);
}

}  // namespace

Image depthmap_picture(const DepthmapResult& r) {
    const int rows = static_cast<int>(r.depth_m.rows()), cols = static_cast<int>(r.depth_m.cols());
    const int gap = 8, bar = std::max(8, cols / 16);
    Image out(rows, 2 * cols + 2 * gap + bar, 3);
    for (auto& c : out.channels) c.setOnes();
    auto inv = [](double u) { return std::isinf(u) ? 0.0 : 1.0 / u; };
    const double near = inv(r.distances_m.front()), far = inv(r.distances_m.back());
    // Confidence in grey from 0 (black) to its largest value (white): its values are small when
    // the cost curves are shallow, and the picture shows where it is high.
    const double cmax = r.confidence.maxCoeff() > 0.0 ? r.confidence.maxCoeff() : 1.0;
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const double t = near == far ? 0.0 : (inv(r.depth_m(i, j)) - near) / (far - near);
            double cr, cg, cb;
            ramp(t, cr, cg, cb);
            out.channels[0](i, j) = cr;
            out.channels[1](i, j) = cg;
            out.channels[2](i, j) = cb;
            for (int k = 0; k < 3; ++k)
                out.channels[k](i, cols + gap + j) = r.confidence(i, j) / cmax;
        }
        // The bar: near at the top, far at the bottom.
        double cr, cg, cb;
        ramp(rows > 1 ? double(i) / (rows - 1) : 0.0, cr, cg, cb);
        for (int j = 2 * cols + 2 * gap; j < 2 * cols + 2 * gap + bar; ++j) {
            out.channels[0](i, j) = cr;
            out.channels[1](i, j) = cg;
            out.channels[2](i, j) = cb;
        }
    }
    return out;
}

}  // namespace pinmask
