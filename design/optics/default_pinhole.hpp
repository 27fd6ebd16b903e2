// The pinhole a camera gets when its user gives every optical length but the pinhole side: the
// whole-pixel pinhole nearest the diffraction optimum at the working distance u, instead of the
// paper's 440 um (which on another camera is neither optimal nor a whole number of pixels per
// cell). Notation as design/optics/working_distance.hpp:
//   d_opt = 1.56 sqrt(lambda |z_eff(u)|)          the optimum with the lens at u
//   N     = max(1, round(d_opt |M(u)| / w))       the whole pixels per cell nearest d_opt's pitch
//   d     = N w / |M(u)|, on the 1 nm grid        exactly N pixels per cell at u
// Where z_eff(u) is infinite (f = f' with u = inf, M = 0) there is no finite optimum and no
// whole-pixel pinhole: the camera's own pinhole is kept, and the note says so.
#pragma once

#include <string>

#include "design/optics/camera.hpp"

namespace pinmask {

struct DefaultPinhole {
    double pinhole_m = 0;           // d: the pinhole to use (the camera's own when not solved)
    double optimum_m = 0;           // d_opt (inf where z_eff is infinite)
    long long pixels_per_cell = 0;  // N (0 when not solved)
    bool solved = false;            // false: no finite optimum, the camera's pinhole kept
    std::string note;               // what was chosen and why, naming `pinhole_m` (a field_ref)
};

// For `camera` (validated; its pinhole only used when nothing can be solved).
DefaultPinhole default_pinhole(const Camera& camera);

// The largest pinhole side validate(Camera) accepts (design/optics/camera.cpp's range of lengths).
// A pinhole solved for N whole pixels per cell above it is refused by the solver's face, naming its
// own flag, before validate would blame a unit left off.
inline constexpr double kMaxPinholeM = 10e-3;
// "needs d = ... for N whole pixels per cell at u, larger than any pinhole ..." when
// `pinhole_m` is above kMaxPinholeM, else empty.
std::string solved_pinhole_too_large(double pinhole_m, long long pixels_per_cell);

// How far the pinhole a solve starts from sits from the optimum: a note naming both and the
// factor when d / d_opt is above `factor` or below 1 / factor, else empty.
inline constexpr double kFarFromOptimumFactor = 2.0;
std::string far_from_optimum_note(const Camera& camera);

}  // namespace pinmask
