// Shared fixtures of the export tests: small masks, and independent geometric references
// (crossing-number point-in-polygon, O(n^2) segment intersection) to check layouts against.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "export/layout/layout.hpp"

namespace pinmask::test {

// The golden mask: 4 x 4 cells of 440 um, pinholes (0,0), (1,2), (3,2), one tile.
inline Mask golden_mask() {
    Mask m;
    m.camera.pinhole_m = 440e-6;
    m.pattern.n = 4;
    m.pattern.tiles_rows = m.pattern.tiles_cols = 1;
    m.pattern.pinholes = {{0, 0}, {1, 2}, {3, 2}};
    return m;
}

// A mask of n x n cells with the given pinholes, spacing rule off (touching allowed).
inline Mask mask_with(int n, std::vector<Cell> holes, int tiles_rows = 1, int tiles_cols = 1,
                      double pinhole_m = 100e-6) {
    Mask m;
    m.camera.pinhole_m = pinhole_m;
    m.pattern.n = n;
    m.pattern.tiles_rows = tiles_rows;
    m.pattern.tiles_cols = tiles_cols;
    m.pattern.min_spacing_cells = 0.0;
    m.pattern.pinholes = std::move(holes);
    m.provenance.spacing_violations_allowed = true;
    return m;
}

// Random occupancy with probability p per cell (seeded): a MURA-like dense touching pattern.
inline Mask random_dense_mask(int n, double p, std::uint64_t seed, int tiles = 1) {
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution coin(p);
    std::vector<Cell> holes;
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            if (coin(rng)) holes.push_back({r, c});
    if (holes.empty()) holes.push_back({0, 0});
    return mask_with(n, holes, tiles, tiles);
}

// Crossing-number test for a point strictly inside or outside (never on the boundary: callers
// sample at half-integer offsets away from every vertex coordinate). Doubles are exact here:
// coordinates are integers below 2^31 and sample points half-integers.
inline bool inside(const Ring& r, double x, double y) {
    bool in = false;
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
        const double xi = double(r[i].x), yi = double(r[i].y);
        const double xj = double(r[j].x), yj = double(r[j].y);
        if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
    }
    return in;
}

inline int orient(const PointNm& a, const PointNm& b, const PointNm& c) {
    const __int128 v = (__int128)(b.x - a.x) * (c.y - a.y) - (__int128)(b.y - a.y) * (c.x - a.x);
    return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

inline bool on_segment(const PointNm& a, const PointNm& b, const PointNm& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

// Closed segments ab and cd share a point.
inline bool segments_meet(const PointNm& a, const PointNm& b, const PointNm& c, const PointNm& d) {
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
              o4 = orient(c, d, b);
    if (o1 != o2 && o3 != o4) return true;
    if (o1 == 0 && on_segment(a, b, c)) return true;
    if (o2 == 0 && on_segment(a, b, d)) return true;
    if (o3 == 0 && on_segment(c, d, a)) return true;
    if (o4 == 0 && on_segment(c, d, b)) return true;
    return false;
}

// Simple polygon: non-adjacent edges never meet, adjacent edges meet only at their shared
// vertex (O(n^2), for small rings).
inline bool is_simple(const Ring& r) {
    const std::size_t n = r.size();
    if (n < 3) return false;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            const PointNm &a = r[i], &b = r[(i + 1) % n], &c = r[j], &d = r[(j + 1) % n];
            const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if (!adjacent) {
                if (segments_meet(a, b, c, d)) return false;
            } else {
                // Adjacent edges must not fold back over each other.
                const PointNm& shared = (j == i + 1) ? b : a;
                const PointNm& p = (j == i + 1) ? a : b;
                const PointNm& q = (j == i + 1) ? d : c;
                if (orient(p, shared, q) == 0 &&
                    (p.x - shared.x) * (q.x - shared.x) + (p.y - shared.y) * (q.y - shared.y) > 0)
                    return false;
            }
        }
    return true;
}

// Number of rings containing the point.
inline int cover_count(const std::vector<Ring>& rings, double x, double y) {
    int k = 0;
    for (const Ring& r : rings) k += inside(r, x, y) ? 1 : 0;
    return k;
}

}  // namespace pinmask::test
