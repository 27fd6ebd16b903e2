#include "export/layout/rings.hpp"

#include <algorithm>

namespace pinmask {
namespace {

WideInt cross(const PointNm& o, const PointNm& a, const PointNm& b) {
    return WideInt(a.x - o.x) * (b.y - o.y) - WideInt(a.y - o.y) * (b.x - o.x);
}

bool less_xy(const PointNm& a, const PointNm& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }

}  // namespace

WideInt doubled_area(const Ring& ring) {
    WideInt s = 0;
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
        const PointNm& p = ring[i];
        const PointNm& q = ring[(i + 1) % n];
        s += WideInt(p.x) * q.y - WideInt(q.x) * p.y;
    }
    return s;
}

BoxNm bounding_box(const std::vector<Ring>& rings) {
    BoxNm b;
    bool first = true;
    for (const Ring& r : rings)
        for (const PointNm& p : r) {
            if (first) {
                b = {p.x, p.y, p.x, p.y};
                first = false;
            }
            b.x0 = std::min(b.x0, p.x);
            b.y0 = std::min(b.y0, p.y);
            b.x1 = std::max(b.x1, p.x);
            b.y1 = std::max(b.y1, p.y);
        }
    return b;
}

BoxNm box_union(const BoxNm& a, const BoxNm& b) {
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

Ring box_ring(const BoxNm& b) { return {{b.x0, b.y0}, {b.x1, b.y0}, {b.x1, b.y1}, {b.x0, b.y1}}; }

Ring simplified(Ring ring) {
    if (ring.size() >= 2 && ring.front() == ring.back()) ring.pop_back();
    // Repeat until stable: removing one vertex can make its neighbours collinear (spikes).
    bool changed = true;
    while (changed && ring.size() >= 3) {
        changed = false;
        Ring out;
        out.reserve(ring.size());
        const std::size_t n = ring.size();
        for (std::size_t i = 0; i < n; ++i) {
            const PointNm& prev = out.empty() ? ring[(i + n - 1) % n] : out.back();
            const PointNm& cur = ring[i];
            const PointNm& next = ring[(i + 1) % n];
            if (cur == prev || cross(prev, cur, next) == 0) {
                changed = true;
                continue;
            }
            out.push_back(cur);
        }
        ring.swap(out);
    }
    if (ring.size() < 3) return {};
    if (doubled_area(ring) < 0) std::reverse(ring.begin(), ring.end());
    return ring;
}

std::vector<Ring> canonical_rings(std::vector<Ring> rings) {
    std::vector<Ring> out;
    out.reserve(rings.size());
    for (Ring& r : rings) {
        Ring s = simplified(std::move(r));
        if (s.empty()) continue;
        const auto first = std::min_element(s.begin(), s.end(), less_xy);
        std::rotate(s.begin(), first, s.end());
        out.push_back(std::move(s));
    }
    std::sort(out.begin(), out.end(), [](const Ring& a, const Ring& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), less_xy);
    });
    return out;
}

Ring mirrored_about_y_axis(const Ring& ring) {
    Ring out(ring.rbegin(), ring.rend());
    for (PointNm& p : out) p.x = -p.x;
    return out;
}

}  // namespace pinmask
