// Periodic finite differences on the torus, the divergence, and isotropic total variation.
//
// Notation: x an R x C plane, indices taken mod R and mod C.
//   (grad x)_r(i, j) = x(i + 1, j) - x(i, j),   (grad x)_c(i, j) = x(i, j + 1) - x(i, j)
//   div(d_r, d_c)(i, j) = d_r(i, j) - d_r(i - 1, j) + d_c(i, j) - d_c(i, j - 1) = -grad^T (d_r,
//   d_c) TV(x) = sum_{i, j} sqrt((grad x)_r^2 + (grad x)_c^2)   (isotropic)
// grad^T grad is diagonalised by the DFT with eigenvalues 4 sin^2(pi k / R) + 4 sin^2(pi l / C),
// so ||grad||^2 <= 8.
#pragma once

#include "core/image/image.hpp"

namespace pinmask {

// The two forward differences of x (resized to x's size).
void gradient(const Plane& x, Plane& d_r, Plane& d_c);

// div(d_r, d_c) = -grad^T (d_r, d_c); d_r and d_c have the same size.
Plane divergence(const Plane& d_r, const Plane& d_c);
// Allocation-free form (out resized when needed; must not alias d_r or d_c).
void divergence(const Plane& d_r, const Plane& d_c, Plane& out);

// Isotropic TV from the differences, and of a plane.
double total_variation(const Plane& d_r, const Plane& d_c);
double total_variation(const Plane& x);

// Eigenvalues of grad^T grad on the half spectrum: rows x (cols / 2 + 1), entry (k, l) =
// 4 sin^2(pi k / rows) + 4 sin^2(pi l / cols).
Plane gradient_gram_symbol(int rows, int cols);

}  // namespace pinmask
