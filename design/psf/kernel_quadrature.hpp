// Gauss-Legendre quadrature on [-1, 1], used by the kernel models to integrate the smooth,
// band-limited pinhole intensity over pixels and to project the Fresnel phase onto Legendre
// polynomials. An m-point rule integrates polynomials of degree <= 2m - 1 exactly.
#pragma once

#include <vector>

namespace pinmask {

struct GaussLegendreRule {
    std::vector<double> nodes;    // ascending, in (-1, 1)
    std::vector<double> weights;  // positive, sum 2
};

// The m-point rule, 1 <= m <= 1000 (InvalidInput otherwise). Nodes by Newton iteration on P_m
// from Tricomi's initial guess; accurate to a few ulps.
GaussLegendreRule gauss_legendre(int m);

// int_a^b fn(x) dx with the rule applied on `panels` equal sub-intervals.
template <class Fn>
double integrate_panels(const GaussLegendreRule& rule, double a, double b, int panels, Fn&& fn) {
    const double h = (b - a) / panels;
    double total = 0.0;
    for (int p = 0; p < panels; ++p) {
        const double mid = a + (p + 0.5) * h, half = 0.5 * h;
        double s = 0.0;
        for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
            s += rule.weights[i] * fn(mid + half * rule.nodes[i]);
        }
        total += s * half;
    }
    return total;
}

}  // namespace pinmask
