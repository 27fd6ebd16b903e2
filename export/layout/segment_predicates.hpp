// Exact predicates on integer-nanometre points and segments for the design-rule check
// (export/pipeline/drc): orientation, segment contact, distance below a bound, point in ring; plus
// the closest approach of two segments in double, for reports. Exact while |coordinate| <= 2^30 nm:
// squared distances and cross products stay below 2^126.
#pragma once

#include <limits>

#include "export/layout/rings.hpp"

namespace pinmask {

__extension__ typedef __int128 Int128;

// (a - o) x (b - o): > 0 when o, a, b turn counter-clockwise.
inline Int128 cross(const PointNm& o, const PointNm& a, const PointNm& b) {
    return Int128(a.x - o.x) * (b.y - o.y) - Int128(a.y - o.y) * (b.x - o.x);
}
inline int sign(Int128 v) { return (v > 0) - (v < 0); }

// Closed segments ab and cd share a point.
bool segments_meet(const PointNm& a, const PointNm& b, const PointNm& c, const PointNm& d);

// |p - segment ab|^2 < g2.
bool point_closer(const PointNm& p, const PointNm& a, const PointNm& b, Int128 g2);

// The distance of two closed segments is below sqrt(g2): they meet, or an endpoint is closer.
bool segments_closer(const PointNm& a, const PointNm& b, const PointNm& c, const PointNm& d,
                     Int128 g2);

// p strictly inside ring r (not on its boundary), by an exact crossing count of a ray to +x.
bool point_inside(const PointNm& p, const Ring& r);

// Closest approach of two segments in double, for reports: the distance and the midpoint of the
// closest pair of points (a crossing point when the segments cross).
struct Approach {
    double dist = std::numeric_limits<double>::infinity();
    double x = 0, y = 0;
};
Approach segment_approach(const PointNm& a, const PointNm& b, const PointNm& c, const PointNm& d);

}  // namespace pinmask
