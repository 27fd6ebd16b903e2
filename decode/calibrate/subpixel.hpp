// Sub-pixel placement of small images by separable Lanczos-3 interpolation (a = 3:
// L(t) = sinc(t) sinc(t / 3) for |t| < 3, else 0; sinc(t) = sin(pi t) / (pi t)). Samples outside
// the source count as 0. Index coordinates: pixel (r, c) has its centre at (c, r).
#pragma once

#include "core/image/image.hpp"

namespace pinmask::calibrate {

inline constexpr int kLanczosA = 3;

double lanczos3(double t);

// Adds weight * kernel to `target`, moved so that the kernel's point (ky, kx) (its own index
// coordinates, usually its centroid) lands on (y, x) of the target; clipped to the target.
// With `wrap` the target is a torus (indices taken modulo its size).
void add_kernel(Plane& target, const Plane& kernel, double ky, double kx, double y, double x,
                double weight, bool wrap = false);

// The window of `source` of size (2 half + 1)^2 whose centre pixel samples the point (y, x)
// (interpolated); samples outside the source are 0.
Plane sample_window(const Plane& source, double y, double x, int half);

// Centroid (y, x) of a plane with positive sum (index coordinates).
void centroid(const Plane& p, double& y, double& x);

}  // namespace pinmask::calibrate
