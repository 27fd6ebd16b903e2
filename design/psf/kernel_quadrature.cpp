#include "design/psf/kernel_quadrature.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {

namespace {

// P_m(x) and its derivative P_m'(x) (|x| < 1), by the three-term recurrence from P_0 = 1, P_1 = x.
struct Legendre {
    double p, dp;
};
Legendre legendre(int m, double x) {
    double p0 = 1.0, p1 = x;
    for (int k = 2; k <= m; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    return {p1, m * (x * p1 - p0) / (x * x - 1.0)};
}

}  // namespace

GaussLegendreRule gauss_legendre(int m) {
    if (m < 1 || m > 1000) {
        throw invalid_field("Gauss-Legendre order", std::to_string(m), "must be in 1..1000");
    }
    GaussLegendreRule rule;
    rule.nodes.assign(m, 0.0);
    rule.weights.assign(m, 0.0);
    for (int i = 0; i < (m + 1) / 2; ++i) {
        // Tricomi's approximation of the i-th largest root, then Newton on P_m.
        double x = std::cos(std::numbers::pi * (i + 0.75) / (m + 0.5));
        for (int it = 0; it < 100; ++it) {
            const Legendre at = legendre(m, x);
            const double dx = at.p / at.dp;
            x -= dx;
            if (std::fabs(dx) <= 1e-16 * std::max(1.0, std::fabs(x))) break;
        }
        // The derivative at the converged root, for the weight.
        const double dp = legendre(m, x).dp;
        const double w = 2.0 / ((1.0 - x * x) * dp * dp);
        rule.nodes[m - 1 - i] = x;
        rule.nodes[i] = -x;
        rule.weights[m - 1 - i] = w;
        rule.weights[i] = w;
    }
    if (m % 2 == 1) rule.nodes[m / 2] = 0.0;
    return rule;
}

}  // namespace pinmask
