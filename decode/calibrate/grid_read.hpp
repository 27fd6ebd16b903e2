// Reading a smooth sampled plane between its nodes: 6-point Lagrange interpolation along each
// axis (exact for polynomials up to degree 5; at half a node a sinusoid of 6.6 nodes per period,
// the phone camera's diffraction fringes, keeps 99.7 % of its amplitude where the bilinear read
// keeps 89 %). The forward fit's diffraction halo is made on a grid along the mask's axes and read
// at the pixels with it (decode/calibrate/forward_fit).
#pragma once

#include <Eigen/Core>

namespace pinmask::calibrate {

using GridF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The weights of nodes -2 .. 3 for the point f (0 <= f < 1) between nodes 0 and 1.
void lagrange6_weights(double f, double w[6]);

// The grid's value at (v, u) in node coordinates (row v, column u); the point must lie at least
// two nodes inside the grid's first node and three before its last along each axis (clamped
// there otherwise).
double read_lagrange6(const GridF& grid, double v, double u);

}  // namespace pinmask::calibrate
