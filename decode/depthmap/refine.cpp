#include "decode/depthmap/refine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {

RefinedDepth refine_depth(const std::vector<Plane>& costs, const std::vector<double>& inv) {
    const std::size_t k_count = costs.size();
    if (k_count == 0 || inv.size() != k_count) {
        throw invalid_field("planes", std::to_string(k_count),
                            "need at least one plane and one distance per plane");
    }
    for (std::size_t k = 1; k < k_count; ++k) {
        if (costs[k].rows() != costs[0].rows() || costs[k].cols() != costs[0].cols()) {
            throw invalid_field("planes", std::to_string(k), "cost planes differ in size");
        }
        if ((inv[k] - inv[k - 1]) * (inv[1] - inv[0]) <= 0.0) {
            throw invalid_field("planes", std::to_string(k), "1/u must be strictly monotonic");
        }
    }
    const Eigen::Index rows = costs[0].rows(), cols = costs[0].cols();
    RefinedDepth out{Plane(rows, cols), Plane(rows, cols), Plane(rows, cols)};
    std::vector<double> c(k_count), sorted(k_count);
    for (Eigen::Index i = 0; i < rows; ++i) {
        for (Eigen::Index j = 0; j < cols; ++j) {
            for (std::size_t k = 0; k < k_count; ++k) c[k] = costs[k](i, j);
            const std::size_t best =
                static_cast<std::size_t>(std::min_element(c.begin(), c.end()) - c.begin());
            double t = 0.0;
            if (best > 0 && best + 1 < k_count) {
                const double a = c[best - 1], b = c[best], d = c[best + 1];
                const double curv = a - 2.0 * b + d;
                if (curv > 0.0) t = std::clamp((a - d) / (2.0 * curv), -0.5, 0.5);
            }
            double x = inv[best];
            if (t > 0.0) x += t * (inv[best + 1] - inv[best]);
            if (t < 0.0) x += -t * (inv[best - 1] - inv[best]);
            out.depth_m(i, j) = x > 0.0 ? 1.0 / x : std::numeric_limits<double>::infinity();
            out.label(i, j) = static_cast<double>(best);
            sorted = c;
            std::nth_element(sorted.begin(), sorted.begin() + k_count / 2, sorted.end());
            const double med = sorted[k_count / 2];
            out.confidence(i, j) = med > 0.0 ? std::clamp((med - c[best]) / med, 0.0, 1.0) : 0.0;
        }
    }
    return out;
}

Plane label_confidence(const std::vector<Plane>& costs, const Plane& label) {
    if (costs.empty()) throw invalid_field("planes", "0", "need at least one plane");
    const std::size_t k_count = costs.size();
    for (const Plane& c : costs) {
        if (c.rows() != label.rows() || c.cols() != label.cols())
            throw invalid_field("planes", "", "cost planes and labels differ in size");
    }
    Plane out(label.rows(), label.cols());
    std::vector<double> sorted(k_count);
    for (Eigen::Index p = 0; p < label.size(); ++p) {
        for (std::size_t k = 0; k < k_count; ++k) sorted[k] = costs[k].data()[p];
        const auto l = static_cast<std::size_t>(label.data()[p]);
        if (l >= k_count) throw invalid_field("planes", std::to_string(l), "label out of range");
        const double chosen = sorted[l];
        std::nth_element(sorted.begin(), sorted.begin() + k_count / 2, sorted.end());
        const double med = sorted[k_count / 2];
        out.data()[p] = med > 0.0 ? std::clamp((med - chosen) / med, 0.0, 1.0) : 0.0;
    }
    return out;
}

}  // namespace pinmask
