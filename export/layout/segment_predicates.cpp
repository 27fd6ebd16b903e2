#include "export/layout/segment_predicates.hpp"

#include <algorithm>
#include <cmath>

namespace pinmask {
namespace {

bool in_box(const PointNm& p, const PointNm& a, const PointNm& b) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

Approach point_approach(const PointNm& p, const PointNm& a, const PointNm& b) {
    const double dx = double(b.x - a.x), dy = double(b.y - a.y);
    const double len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? (double(p.x - a.x) * dx + double(p.y - a.y) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const double qx = double(a.x) + t * dx, qy = double(a.y) + t * dy;
    return {std::hypot(double(p.x) - qx, double(p.y) - qy), 0.5 * (p.x + qx), 0.5 * (p.y + qy)};
}

}  // namespace

// Closed segments ab and cd share a point (exact).
bool segments_meet(const PointNm& a, const PointNm& b, const PointNm& c, const PointNm& d) {
    const int d1 = sign(cross(a, b, c)), d2 = sign(cross(a, b, d));
    const int d3 = sign(cross(c, d, a)), d4 = sign(cross(c, d, b));
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && in_box(c, a, b)) || (d2 == 0 && in_box(d, a, b)) ||
           (d3 == 0 && in_box(a, c, d)) || (d4 == 0 && in_box(b, c, d));
}

// |p - segment ab|^2 < g2, exact.
bool point_closer(const PointNm& p, const PointNm& a, const PointNm& b, Int128 g2) {
    const Int128 dx = b.x - a.x, dy = b.y - a.y, wx = p.x - a.x, wy = p.y - a.y;
    const Int128 t = dx * wx + dy * wy;
    if (t <= 0) return wx * wx + wy * wy < g2;
    const Int128 len2 = dx * dx + dy * dy;
    if (t >= len2) {
        const Int128 ex = p.x - b.x, ey = p.y - b.y;
        return ex * ex + ey * ey < g2;
    }
    const Int128 c = dx * wy - dy * wx;
    return c * c < g2 * len2;
}

// The distance of two closed segments is < g (exact): they meet, or an endpoint is closer.
bool segments_closer(const PointNm& a, const PointNm& b, const PointNm& c, const PointNm& d,
                     Int128 g2) {
    return segments_meet(a, b, c, d) || point_closer(a, c, d, g2) || point_closer(b, c, d, g2) ||
           point_closer(c, a, b, g2) || point_closer(d, a, b, g2);
}

Approach segment_approach(const PointNm& a, const PointNm& b, const PointNm& c, const PointNm& d) {
    Approach best;
    for (const Approach& t : {point_approach(a, c, d), point_approach(b, c, d),
                              point_approach(c, a, b), point_approach(d, a, b)}) {
        if (t.dist < best.dist) best = t;
    }
    if (best.dist > 0 && segments_meet(a, b, c, d)) {  // proper crossing: intersect the lines
        const double den = double(cross({0, 0}, {b.x - a.x, b.y - a.y}, {d.x - c.x, d.y - c.y}));
        const double s = double(cross(c, d, a)) / den;  // a + s (b - a) lies on line cd
        best = {0.0, a.x + s * double(b.x - a.x), a.y + s * double(b.y - a.y)};
    }
    return best;
}

// p strictly inside ring r (p not on its boundary), exact crossing count of a ray to +x.
bool point_inside(const PointNm& p, const Ring& r) {
    bool inside = false;
    for (std::size_t k = 0, n = r.size(); k < n; ++k) {
        const PointNm& a = r[k];
        const PointNm& b = r[(k + 1) % n];
        if ((a.y > p.y) == (b.y > p.y)) continue;
        const int s = sign(cross(a, b, p));
        if ((b.y > a.y && s > 0) || (b.y < a.y && s < 0)) inside = !inside;
    }
    return inside;
}

}  // namespace pinmask
