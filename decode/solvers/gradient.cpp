#include "decode/solvers/gradient.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace pinmask {

void gradient(const Plane& x, Plane& d_r, Plane& d_c) {
    const Eigen::Index R = x.rows(), C = x.cols();
    d_r.resize(R, C);
    d_c.resize(R, C);
    if (R == 0 || C == 0) return;
    d_r.topRows(R - 1) = x.bottomRows(R - 1) - x.topRows(R - 1);
    d_r.row(R - 1) = x.row(0) - x.row(R - 1);
    d_c.leftCols(C - 1) = x.rightCols(C - 1) - x.leftCols(C - 1);
    d_c.col(C - 1) = x.col(0) - x.col(C - 1);
}

Plane divergence(const Plane& d_r, const Plane& d_c) {
    Plane out;
    divergence(d_r, d_c, out);
    return out;
}

void divergence(const Plane& d_r, const Plane& d_c, Plane& out) {
    const Eigen::Index R = d_r.rows(), C = d_r.cols();
    out.resize(R, C);
    if (R == 0 || C == 0) return;
    out.bottomRows(R - 1) = d_r.bottomRows(R - 1) - d_r.topRows(R - 1);
    out.row(0) = d_r.row(0) - d_r.row(R - 1);
    out.rightCols(C - 1) += d_c.rightCols(C - 1) - d_c.leftCols(C - 1);
    out.col(0) += d_c.col(0) - d_c.col(C - 1);
}

double total_variation(const Plane& d_r, const Plane& d_c) {
    return (d_r.square() + d_c.square()).sqrt().sum();
}

double total_variation(const Plane& x) {
    Plane d_r, d_c;
    gradient(x, d_r, d_c);
    return total_variation(d_r, d_c);
}

Plane gradient_gram_symbol(int rows, int cols) {
    const int hc = cols / 2 + 1;
    Plane s(rows, hc);
    // The column terms once (rows + hc sines instead of rows hc: this runs in every solver's
    // set-up); the same values as computing each entry on its own.
    std::vector<double> sl2(static_cast<std::size_t>(hc));
    for (int l = 0; l < hc; ++l) {
        const double sl = std::sin(std::numbers::pi * l / cols);
        sl2[static_cast<std::size_t>(l)] = sl * sl;
    }
    for (int k = 0; k < rows; ++k) {
        const double sk = std::sin(std::numbers::pi * k / rows);
        for (int l = 0; l < hc; ++l) s(k, l) = 4.0 * (sk * sk + sl2[static_cast<std::size_t>(l)]);
    }
    return s;
}

}  // namespace pinmask
