// Shared references for the decode/ tests: seeded random planes and PSFs, and the dense
// circulant matrix of a PSF built straight from the deconvwnr centring rule (independent of
// decode/solvers/psf2otf.cpp).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "core/image/image.hpp"
#include "decode/solvers/convolution.hpp"
#include "tests/support/random_plane.hpp"

namespace pinmask::test {

// A positive PSF normalised to sum 1, with a dominant centre so its OTF stays away from zero.
inline Plane random_psf(int rows, int cols, unsigned seed) {
    Plane a = random_plane(rows, cols, seed, 0.0, 1.0);
    a(rows / 2, cols / 2) += 1.0 * rows * cols;  // centre >= 2/3 of the mass: |H| >= 1/3
    return a / a.sum();
}

// Row-major flattening index of pixel (r, c) on an R x C grid.
inline Eigen::Index flat(Eigen::Index r, Eigen::Index c, Eigen::Index cols) { return r * cols + c; }

// Dense matrix of circular convolution with `psf` on an R x C torus, the PSF's element
// (floor(pr/2), floor(pc/2)) acting as the origin: (A x)(i + r - cr, j + c - cc) += psf(r, c) x(i,
// j).
inline Eigen::MatrixXd dense_circulant(const Plane& psf, int R, int C) {
    const Eigen::Index n = Eigen::Index(R) * C;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    const Eigen::Index cr = psf.rows() / 2, cc = psf.cols() / 2;
    for (int i = 0; i < R; ++i)
        for (int j = 0; j < C; ++j)
            for (Eigen::Index r = 0; r < psf.rows(); ++r)
                for (Eigen::Index c = 0; c < psf.cols(); ++c) {
                    const Eigen::Index oi = ((i + r - cr) % R + R) % R;
                    const Eigen::Index oj = ((j + c - cc) % C + C) % C;
                    A(flat(oi, oj, C), flat(i, j, C)) += psf(r, c);
                }
    return A;
}

// Dense periodic forward-difference matrices (rows and columns directions).
inline Eigen::MatrixXd dense_difference(int R, int C, bool along_rows) {
    const Eigen::Index n = Eigen::Index(R) * C;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < R; ++i)
        for (int j = 0; j < C; ++j) {
            const Eigen::Index k = flat(i, j, C);
            D(k, along_rows ? flat((i + 1) % R, j, C) : flat(i, (j + 1) % C, C)) += 1.0;
            D(k, k) -= 1.0;
        }
    return D;
}

// Dense matrix of a ConvolutionOperator (capture pixels x working pixels), column by column from
// the direct circulant matrix on the working grid followed by the crop (independent of FFTs).
inline Eigen::MatrixXd dense_model(const Plane& psf, const ConvGeometry& g) {
    const Eigen::MatrixXd Hd = dense_circulant(psf, g.work_rows, g.work_cols);
    Eigen::MatrixXd A(Eigen::Index(g.capture_rows) * g.capture_cols, Hd.cols());
    for (int i = 0; i < g.capture_rows; ++i)
        for (int j = 0; j < g.capture_cols; ++j)
            A.row(flat(i, j, g.capture_cols)) =
                Hd.row(flat(i + g.crop_row, j + g.crop_col, g.work_cols));
    return A;
}

inline Eigen::VectorXd as_vector(const Plane& p) {
    return Eigen::Map<const Eigen::VectorXd>(p.data(), p.size());
}

inline Plane as_plane(const Eigen::VectorXd& v, int rows, int cols) {
    return Eigen::Map<const Plane>(v.data(), rows, cols);
}

}  // namespace pinmask::test

namespace pinmask::test {

// High-accuracy reference for TV-L2 on small cyclic problems, independent of decode/'s solvers:
// Newton's method with backtracking on the smoothed objective
//   f_delta(x) = 1/2 ||A x - p||^2 + lambda sum_i sqrt(|(grad x)_i|^2 + delta^2),
// dense Eigen Hessians, continuation delta = 1e-1 ... 1e-9. Since 0 <= f_delta - f <= lambda N
// delta for every x, the returned x has TV-L2 objective within lambda N 1e-9 of the minimum (plus
// the Newton stopping error). A is the dense matrix of the model (measurements x R C); a fat
// A (linear model) is fine: the smoothed TV term makes the Hessian positive definite.
inline Eigen::VectorXd smoothed_tv_reference(const Eigen::MatrixXd& A, const Eigen::VectorXd& p,
                                             double lambda, int R, int C) {
    const Eigen::Index n = Eigen::Index(R) * C;
    const Eigen::MatrixXd AtA = A.transpose() * A;
    const Eigen::VectorXd Atp = A.transpose() * p;
    auto down = [&](Eigen::Index k) { return flat((k / C + 1) % R, k % C, C); };
    auto right = [&](Eigen::Index k) { return flat(k / C, (k % C + 1) % C, C); };
    auto value = [&](const Eigen::VectorXd& x, double delta) {
        double tv = 0.0;
        for (Eigen::Index k = 0; k < n; ++k) {
            const double gr = x(down(k)) - x(k), gc = x(right(k)) - x(k);
            tv += std::sqrt(gr * gr + gc * gc + delta * delta);
        }
        return 0.5 * (A * x - p).squaredNorm() + lambda * tv;
    };
    Eigen::VectorXd x = (AtA + 1e-3 * Eigen::MatrixXd::Identity(n, n)).ldlt().solve(Atp);
    for (double delta = 1e-1; delta >= 0.99e-9; delta /= 10.0) {
        for (int it = 0; it < 100; ++it) {
            Eigen::VectorXd grad = AtA * x - Atp;
            Eigen::MatrixXd hess = AtA;
            for (Eigen::Index k = 0; k < n; ++k) {
                const Eigen::Index kd = down(k), kr = right(k);
                const double gr = x(kd) - x(k), gc = x(kr) - x(k);
                const double phi = std::sqrt(gr * gr + gc * gc + delta * delta);
                // d/dx of phi through gr = x_kd - x_k and gc = x_kr - x_k.
                const double wr = lambda * gr / phi, wc = lambda * gc / phi;
                grad(kd) += wr;
                grad(k) -= wr + wc;
                grad(kr) += wc;
                const double p3 = phi * phi * phi;
                const double a = lambda * (1.0 / phi - gr * gr / p3);
                const double b = lambda * (-gr * gc / p3);
                const double c = lambda * (1.0 / phi - gc * gc / p3);
                // e_r = e_kd - e_k, e_c = e_kr - e_k: add a e_r e_r^T + b (e_r e_c^T + e_c e_r^T)
                // + c e_c e_c^T.
                const Eigen::Index idx[3] = {k, kd, kr};
                const double er[3] = {-1.0, 1.0, 0.0}, ec[3] = {-1.0, 0.0, 1.0};
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j)
                        hess(idx[i], idx[j]) += a * er[i] * er[j] +
                                                b * (er[i] * ec[j] + ec[i] * er[j]) +
                                                c * ec[i] * ec[j];
            }
            const Eigen::VectorXd step = hess.ldlt().solve(-grad);
            const double decrement = -grad.dot(step);
            if (decrement < 1e-24 * (1.0 + std::abs(value(x, delta)))) break;
            const double f0 = value(x, delta);
            double t = 1.0;
            while (value(x + t * step, delta) > f0 - 0.25 * t * decrement && t > 1e-12) t *= 0.5;
            x += t * step;
        }
    }
    return x;
}

}  // namespace pinmask::test
