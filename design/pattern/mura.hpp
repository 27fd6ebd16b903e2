// MURA baseline patterns: modified uniformly redundant arrays of prime order p = 4m + 1
// (Gottesman & Fenimore, "New family of binary arrays for coded aperture imaging",
// Appl. Opt. 28, 4344 (1989)). Convention, with i = row and j = col (0-based) on the p x p
// torus and C_i = +1 when i is a nonzero quadratic residue mod p, -1 otherwise:
//   A(0, j) = 0 for every j      (row 0 closed)
//   A(i, 0) = 1 for i != 0       (column 0 open, except the corner)
//   A(i, j) = 1 if C_i C_j = +1, else 0   (i, j != 0)
// giving (p^2 - 1) / 2 open cells. The decoding array is G(0, 0) = +1, otherwise G = 2 A - 1;
// the periodic correlation sum_kl A(k, l) G(k + i, l + j) is (p^2 - 1) / 2 at (0, 0), else 0.
// A URA is p x (p + 2), not square, so it has no place on our n x n torus and is not provided.
// MURAs are half open: they always break a spacing rule of more than 1 cell (column 0 is a run
// of open cells), so a mask built from one must record that violations were allowed.
#pragma once

#include <vector>

#include "design/pattern/pattern.hpp"

namespace pinmask {

// True when v is prime (trial division; v <= kMaxGrid in practice).
bool is_prime(int v);

// The MURA of order p as a pattern. Throws InvalidInput naming `n` when p is not a prime with
// p % 4 == 1 or exceeds kMaxGrid. The spacing rule is not checked here (see
// spacing_violations()); min_spacing_cells and tiles are recorded as given.
Pattern mura_pattern(int p, double min_spacing_cells = 2.0, int tiles_rows = 2, int tiles_cols = 2);

// The decoding array G above, row-major (index row * p + col), entries +1 / -1. Same
// preconditions as mura_pattern.
std::vector<int> mura_decoding_array(int p);

}  // namespace pinmask
