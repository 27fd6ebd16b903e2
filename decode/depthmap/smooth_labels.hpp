// Smoothness on the depth labels: semi-global aggregation of the plane sweep's cost volume
// (Hirschmueller's semi-global matching), dynamic programming along several straight paths.
//
// The energy over a labelling l (one plane index per pixel, planes ordered by 1/u):
//   E(l) = sum_p C_p(l_p) + sum_{neighbours p, q} V(l_p - l_q),
//   V(0) = 0, V(+-1) = p1, V(|delta| >= 2) = p2 (p2 >= p1 >= 0: a step of one plane is cheap, a
//   jump costs p2 whatever its size, so depth edges stay sharp).
// Along one path direction r the cost of ending at pixel p with label d is the exact minimum of
// the energy of the chain of pixels that leads to p along r (pixels outside the frame end it):
//   L_r(p, d) = C_p(d) + min_d' [L_r(p - r, d') + V(d - d')] - min_d' L_r(p - r, d')
// (the last term is a constant per pixel that keeps the sums bounded). The aggregate is
//   S(p, d) = C_p(d) + sum_r [L_r(p, d) - C_p(d)]:
// the data term once plus every path's message. On a one-row volume with the two row paths this
// is the exact min-marginal of E up to a constant per pixel, so argmin_d S is the exact minimiser
// of E (dynamic programming on a chain); on a grid it is the semi-global approximation.
#pragma once

#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

// paths: 2 (along rows, both senses), 4 (and along columns) or 8 (and both diagonals).
// costs: K >= 1 planes of one size. Returns S, K planes of that size. InvalidInput naming the
// field otherwise.
std::vector<Plane> aggregate_paths(const std::vector<Plane>& costs, double p1, double p2,
                                   int paths);

// The scale that makes a smoothness weight independent of the capture's brightness: the mean
// over the pixels of (median_k C_p(k) - min_k C_p(k)), the typical depth of a pixel's cost
// well (the median is the upper middle, as in decode/depthmap/refine). 0 for a flat volume.
double cost_well_depth(const std::vector<Plane>& costs);

}  // namespace pinmask
