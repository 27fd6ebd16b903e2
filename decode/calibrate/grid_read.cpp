#include "decode/calibrate/grid_read.hpp"

#include <algorithm>
#include <cmath>

namespace pinmask::calibrate {

void lagrange6_weights(double f, double w[6]) {
    // w_j = prod over i != j of (f - i) / (j - i), nodes i, j in -2 .. 3.
    for (int j = -2; j <= 3; ++j) {
        double num = 1.0, den = 1.0;
        for (int i = -2; i <= 3; ++i) {
            if (i == j) continue;
            num *= f - i;
            den *= j - i;
        }
        w[j + 2] = num / den;
    }
}

double read_lagrange6(const GridF& grid, double v, double u) {
    const long nv = grid.rows(), nu = grid.cols();
    const long iv = std::clamp(static_cast<long>(std::floor(v)), 2L, std::max(2L, nv - 4));
    const long iu = std::clamp(static_cast<long>(std::floor(u)), 2L, std::max(2L, nu - 4));
    double wv[6], wu[6];
    lagrange6_weights(std::clamp(v - iv, 0.0, 1.0), wv);
    lagrange6_weights(std::clamp(u - iu, 0.0, 1.0), wu);
    double acc = 0.0;
    for (int a = 0; a < 6; ++a) {
        const float* row = grid.data() + (iv - 2 + a) * nu + (iu - 2);
        double s = 0.0;
        for (int b = 0; b < 6; ++b) s += wu[b] * row[b];
        acc += wv[a] * s;
    }
    return acc;
}

}  // namespace pinmask::calibrate
