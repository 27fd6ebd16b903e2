#include "decode/solvers/noise_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pinmask {

// The median of |N(0, 1)|: Phi^-1(3/4).
constexpr double kMadToSigma = 0.6744897501960817;

double estimate_noise_sigma(const Plane& capture) {
    const Eigen::Index rows = capture.rows() / 2, cols = capture.cols() / 2;
    if (rows == 0 || cols == 0) return 0.0;
    std::vector<double> d;
    d.reserve(static_cast<size_t>(rows * cols));
    for (Eigen::Index r = 0; r < rows; ++r) {
        for (Eigen::Index c = 0; c < cols; ++c) {
            const double v = capture(2 * r, 2 * c) - capture(2 * r, 2 * c + 1) -
                             capture(2 * r + 1, 2 * c) + capture(2 * r + 1, 2 * c + 1);
            d.push_back(std::abs(0.5 * v));
        }
    }
    // The upper median for an even count (deterministic, no averaging).
    const auto mid = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
    std::nth_element(d.begin(), mid, d.end());
    return *mid / kMadToSigma;
}

}  // namespace pinmask
