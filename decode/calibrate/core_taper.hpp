// The split of a spot's kernel between the forward fit's core window and its halo
// (decode/calibrate/forward_fit): along one mask axis the core's weight is T(x) = 1 out to the core
// half width c, then cos^2 down to 0 over `width` pixels. A spot's core is its kernel times
// T(u) T(v) at its offsets (u, v) along the mask's axes, the halo the kernel times
// 1 - T(u) T(v). The split is smooth, so the halo's grid (made along the mask's axes, read at
// the pixels by decode/calibrate/grid_read) holds no step at the core's edge, and the core's
// edge is the same square of the mask's axes for both, whatever the rotation. With a hard edge
// along the pixel axes for the core and along the mask's for the halo, the rotated square's
// slivers were counted twice or not at all.
#pragma once

#include <cmath>
#include <numbers>

namespace pinmask::calibrate {

inline constexpr double kTaperPx = 4.0;

struct Taper {
    double c = 0.0, width = 0.0;
    double value(double x) const {
        const double a = std::abs(x) - c;
        if (a <= 0) return 1.0;
        if (a >= width) return 0.0;
        const double cs = std::cos(0.5 * std::numbers::pi * a / width);
        return cs * cs;
    }
    // dT/dx.
    double slope(double x) const {
        const double a = std::abs(x) - c;
        if (a <= 0 || a >= width) return 0.0;
        const double d = -0.5 * std::numbers::pi / width * std::sin(std::numbers::pi * a / width);
        return x < 0 ? -d : d;
    }
    double reach() const { return c + width; }
};

}  // namespace pinmask::calibrate
