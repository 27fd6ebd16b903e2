// From the cost volume of a plane sweep to a depth per pixel: the winning plane (lowest cost),
// a sub-plane refinement by a parabola through the costs of the winner and its two neighbours,
// and a confidence.
//   Planes are ordered by 1/u (the sweep's axis: the pattern's scale is linear in 1/u, Eq. (3)).
//   Parabola: offset t = (c[-1] - c[+1]) / (2 (c[-1] - 2 c[0] + c[+1])), clamped to [-1/2, 1/2],
//   0 at either end of the sweep or where the curvature is not positive; the refined inverse
//   distance is 1/u_k + t (1/u_(k+1) - 1/u_k) (t > 0) or + |t| (1/u_(k-1) - 1/u_k) (t < 0).
//   Confidence: (median_k c - min_k c) / median_k c, in [0, 1] for costs >= 0; 0 when the
//   median is 0 (no plane is preferred), 1 when the winner's cost is 0 and the median's is not.
#pragma once

#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

struct RefinedDepth {
    Plane depth_m;     // refined distance, metres (inf where the refinement reaches 1/u = 0)
    Plane label;       // index of the winning plane (0-based, as a number)
    Plane confidence;  // in [0, 1]
};

// costs[k] and inverse_m[k] (1/u of plane k, strictly monotonic in k) for K >= 1 planes of one
// size. InvalidInput naming the field otherwise.
RefinedDepth refine_depth(const std::vector<Plane>& costs, const std::vector<double>& inverse_m);

// The confidence formula above for a given plane per pixel (label: plane indices as numbers),
// in place of the lowest-cost one: (median_k c - c[label]) / median_k c, clamped to [0, 1]; 0
// when the median is 0. Equals refine_depth's confidence where label is the lowest-cost plane.
Plane label_confidence(const std::vector<Plane>& costs, const Plane& label);

}  // namespace pinmask
