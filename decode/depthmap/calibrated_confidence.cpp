#include "decode/depthmap/calibrated_confidence.hpp"

#include <cmath>

namespace pinmask {

double margin_probability(double m) {
    const auto& k = kMarginProbabilityKnots;
    if (!(m > k.front().first)) return k.front().second;
    if (m >= k.back().first) return k.back().second;
    for (std::size_t i = 1; i < k.size(); ++i) {
        if (m < k[i].first) {
            const double t = (m - k[i - 1].first) / (k[i].first - k[i - 1].first);
            return k[i - 1].second + t * (k[i].second - k[i - 1].second);
        }
    }
    return k.back().second;
}

Plane calibrated_confidence(const Plane& margin) {
    return margin.unaryExpr([](double m) { return margin_probability(m); });
}

}  // namespace pinmask
