// Clipped light in a point-source capture whose ceiling nobody stated (a float file, an array
// from Python): light beyond the sensor's or a conversion's ceiling leaves a flat top, many pixels
// at exactly the capture's largest value. Such spots have biased centroids, gains and kernel, and
// the fit ends at chi^2/dof far above 1 without saying why (a float capture clipped at half its
// peak calibrated at chi^2/dof 20.6). Integer files carry their ceiling (their largest count);
// this finds it for the others. And the capture's scale: the fit works in the capture's units
// between kMinCapturePeak and kMaxCapturePeak (a capture scaled by 1e300 failed as "Fisher
// information is singular").
#pragma once

#include <cstddef>
#include <limits>

#include "core/image/image.hpp"

namespace pinmask::calibrate {

// At least this many pixels at exactly the maximum make a plateau.
inline constexpr std::size_t kMinPlateauPixels = 16;

struct SaturatedPlateau {
    bool found = false;
    std::size_t pixels = 0;                                   // pixels at exactly `level`
    double level = std::numeric_limits<double>::quiet_NaN();  // the capture's largest value
};

// A plateau: at least kMinPlateauPixels pixels at exactly the capture's largest value, one of
// them with at least 3 of its 4 neighbours there too (a flat top: the peak of an unclipped spot,
// even one centred between pixels, has at most 2 neighbours at its value). `pixels` and `level`
// are filled whether or not it is found.
SaturatedPlateau find_saturated_plateau(const Plane& capture);

// The capture's largest |value| must lie in [kMinCapturePeak, kMaxCapturePeak] (0 excepted: a
// dark capture has no spots, said as such). Measured on a rendered capture (peak 700) scaled by
// powers of ten: identical fits from 1e-6 to 1e30 times, no spots at 1e-10 (the spot detector's
// noise floor, 1e-6 absolute), a singular Fisher information at 1e50.
inline constexpr double kMinCapturePeak = 1e-4;
inline constexpr double kMaxCapturePeak = 1e24;
// Throws InvalidInput naming the capture's largest value and the range.
void check_capture_scale(const Plane& capture);

}  // namespace pinmask::calibrate
