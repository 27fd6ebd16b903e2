// The depth map's confidence as a probability: the cost margin of a pixel's plane (decode/depthmap/
// refine label_confidence: (median cost - chosen cost) / median cost) mapped to the share of
// pixels within one plane spacing of the truth at that margin.
//   The map is piecewise linear through the knots below (clamped outside them), the
//   non-decreasing (pool-adjacent-violators) fit of the share within one spacing in margin bins
//   0.05 wide, measured on the scenes of docs/depth.md section 3a rendered by the independent
//   numpy model for the machine-vision and visible 35 mm cameras only (seed 1, 16 planes over each
//   camera's range, window 121, smoothing 8; flat pixels counted as misses), capped at 0.95: a
//   share measured on a handful of scenes is not a certainty. Its reliability is reported on the
//   other two cameras (docs/depth.md section 3c), never fitted there.
#pragma once

#include <array>
#include <utility>

#include "core/image/image.hpp"

namespace pinmask {

// (margin, probability) knots, margins increasing.
inline constexpr std::array<std::pair<double, double>, 7> kMarginProbabilityKnots{{
    {0.025, 0.213},
    {0.075, 0.254},
    {0.125, 0.337},
    {0.175, 0.605},
    {0.225, 0.646},
    {0.275, 0.95},
    {0.325, 0.95},
}};

// The probability of one margin (any real; NaN maps to the lowest knot's probability).
double margin_probability(double margin);

// margin_probability of every pixel.
Plane calibrated_confidence(const Plane& margin);

}  // namespace pinmask
