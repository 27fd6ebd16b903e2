// Registration of a square lattice to spot centroids: rotation, pitch along both axes and
// position, with uncertainties.
// Model (index coordinates, x = column, y = row; i = lattice column index, j = lattice row index):
//   x = x0 + px cos(t) i - py sin(t) j
//   y = y0 + px sin(t) i + py cos(t) j
// Coarse: the lattice score sum over neighbour vectors v (|v| <= kNeighbourCells cells) of
// cos(2 pi u_x) + cos(2 pi u_y), u = R(-t) v / s, on a grid of t in [-max_rotation, +max_rotation]
// and s in nominal_pitch * [1 - pitch_range, 1 + pitch_range]. Fine: integer indices from the
// coarse lattice, then Gauss-Newton least squares over (x0, y0, t, px, py) with outliers
// (residual > kOutlierSigmas robust sigmas) dropped, indices reassigned, three rounds. The
// covariance is s^2 (J^T J)^-1, s^2 = RSS / (2 M - 5) over the M spots kept.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace pinmask::calibrate {

struct LatticeFit {
    double x0 = 0.0, y0 = 0.0;  // position of lattice index (0, 0): the reference spot's site
    double rotation_rad = 0.0;
    double pitch_x_px = 0.0, pitch_y_px = 0.0;
    // 1-sigma uncertainties from the covariance.
    double x0_sigma = 0.0, y0_sigma = 0.0, rotation_sigma_rad = 0.0, pitch_x_sigma_px = 0.0,
           pitch_y_sigma_px = 0.0;
    double residual_rms_px = 0.0;  // over the spots kept
    int spots_used = 0;
    Eigen::Vector2d position(double i, double j) const;  // the model above
    Eigen::Vector2d indices(double x, double y) const;   // its inverse: (i, j), real
};

struct RegistrationOptions {
    double nominal_pitch_px = 8.0;
    double pitch_range = 0.05;       // +- fraction searched around nominal_pitch_px
    double max_rotation_deg = 5.0;   // +- searched
    double max_index_offset = 0.25;  // |i - round(i)| allowed for a spot to sit on the lattice
};

inline constexpr double kNeighbourCells = 4.5;  // neighbour vectors used by the coarse score
inline constexpr double kOutlierSigmas = 4.0;

// Fits the lattice to the points (x, y). Throws InvalidInput when fewer than 3 points sit on any
// lattice in the searched range (naming the rotation and pitch ranges searched).
LatticeFit fit_lattice(const std::vector<Eigen::Vector2d>& points,
                       const RegistrationOptions& options);

}  // namespace pinmask::calibrate
