// Shared references for the decode/ tests: seeded random planes and PSFs, and the dense
// circulant matrix of a PSF built straight from the deconvwnr centring rule (independent of
// decode/psf2otf.cpp).
#pragma once

#include <Eigen/Dense>
#include <random>

#include "core/image.hpp"

namespace pinmask::test {

inline Plane random_plane(int rows, int cols, unsigned seed, double lo = -1.0, double hi = 1.0) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    Plane p(rows, cols);
    for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = u(rng);
    return p;
}

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

inline Eigen::VectorXd as_vector(const Plane& p) {
    return Eigen::Map<const Eigen::VectorXd>(p.data(), p.size());
}

inline Plane as_plane(const Eigen::VectorXd& v, int rows, int cols) {
    return Eigen::Map<const Plane>(v.data(), rows, cols);
}

}  // namespace pinmask::test
