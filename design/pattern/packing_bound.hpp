// How many pinholes fit on an n x n torus under the spacing rule (design/pattern/pattern.hpp): a
// proven upper bound and a verified lattice placement (a lower bound). Used to refuse infeasible
// requests with the numbers instead of searching forever.
// Notation: n grid size, s = min_spacing_cells, K number of pinholes.
#pragma once

#include <string>
#include <vector>

#include "design/pattern/pattern.hpp"

namespace pinmask {

struct PackingUpperBound {
    long long count = 0;  // no valid placement holds more pinholes
    std::string reason;   // the argument that proves it, in words
};

// The smallest of these proven bounds:
//  - n < s: 0 (a pinhole is closer than s to its own periodic copy);
//  - n^2 (one pinhole per cell);
//  - strips: a band of a consecutive rows (a <= n, a - 1 < s) holds pinholes whose columns are
//    pairwise >= g apart on the n-cycle, g = the least c with (a-1)^2 + c^2 >= s^2, so at most
//    floor(n/g) of them; each row lies in a of the n bands: K <= floor(n floor(n/g) / a).
//    (s = 2: K <= floor(n floor(n/2) / 2), exact for every n; (n/2)^2 for even n.)
//  - disks: disks of radius s/2 around the pinholes are disjoint on the torus, and a torus
//    packing is a periodic plane packing, whose density is at most pi/sqrt(12) (Thue,
//    Fejes Toth): K <= 2 n^2 / (sqrt(3) s^2).
// O(s) time.
PackingUpperBound packing_upper_bound(int n, double min_spacing_cells);

struct LatticePlacement {
    std::vector<Cell> cells;  // valid under the rule, checked with spacing_violations()
    std::string description;  // e.g. "rows every 2, columns every 2, shift 0"
};

// The best of a few lattices {i (p, t) + j (0, q)} clipped to the torus, with the points that
// clash across the seams dropped greedily; the result is verified against the rule (a
// RuntimeFailure if not: that would be a bug). O(n^2) time and memory.
LatticePlacement lattice_placement(int n, double min_spacing_cells);

}  // namespace pinmask
