#include "export/layout/xor_area.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <optional>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;  // exact predicates suffice
using Polygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;
using PolygonSet = CGAL::Polygon_set_2<Kernel>;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
__extension__ typedef __int128 Int128;
__extension__ typedef unsigned __int128 UInt128;

// The ring validated (>= 3 vertices, coordinates in range, simple) in canonical form:
// counter-clockwise, starting at its smallest (x, y) vertex. `field` names it in errors.
Ring canonical(const Ring& ring, const std::string& field) {
    if (ring.size() < 3) {
        throw invalid_field(field, std::to_string(ring.size()) + " vertices",
                            "a polygon needs at least 3 vertices");
    }
    std::vector<Epick::Point_2> pts;
    pts.reserve(ring.size());
    for (const PointNm& v : ring) {
        if (std::max(std::abs(v.x), std::abs(v.y)) > kMaxCoordNm) {
            throw invalid_field(
                field, std::to_string(v.x) + ", " + std::to_string(v.y),
                "coordinates must be within +-" + std::to_string(kMaxCoordNm) + " nm");
        }
        pts.emplace_back(double(v.x), double(v.y));  // |coordinate| <= 2^30: exact in double
    }
    if (!CGAL::is_simple_2(pts.begin(), pts.end(), Epick())) {
        throw invalid_field(field, "a self-intersecting or repeated-vertex ring",
                            "area comparison needs simple polygons");
    }
    Ring r = ring;
    if (CGAL::orientation_2(pts.begin(), pts.end(), Epick()) == CGAL::CLOCKWISE) {
        std::reverse(r.begin(), r.end());
    }
    const auto first = std::min_element(r.begin(), r.end(), [](const PointNm& p, const PointNm& q) {
        return p.x != q.x ? p.x < q.x : p.y < q.y;
    });
    std::rotate(r.begin(), first, r.end());
    return r;
}

// Twice the area of a counter-clockwise ring, exact (|coordinate| <= 2^30).
Int128 doubled_area(const Ring& r) {
    Int128 a = 0;
    for (std::size_t k = 0, n = r.size(); k < n; ++k) {
        const PointNm &p = r[k], &q = r[(k + 1) % n];
        a += Int128(p.x) * q.y - Int128(q.x) * p.y;
    }
    return a;
}

// An axis-aligned rectangle (4 vertices, canonical order) as a box, if the ring is one.
std::optional<BoxNm> as_box(const Ring& r) {
    if (r.size() != 4) return std::nullopt;
    // Canonical CCW from the lower-left corner: (x0,y0) (x1,y0) (x1,y1) (x0,y1).
    if (r[1].y == r[0].y && r[2].x == r[1].x && r[3].y == r[2].y && r[3].x == r[0].x) {
        return BoxNm{r[0].x, r[0].y, r[2].x, r[2].y};
    }
    return std::nullopt;
}

Kernel::FT to_ft(Int128 v) {
    // Three 42-bit limbs, each exact in a double.
    const bool negative = v < 0;
    UInt128 u = negative ? -static_cast<UInt128>(v) : static_cast<UInt128>(v);
    const double limb = 4398046511104.0;  // 2^42
    Kernel::FT out = 0, scale = 1;
    for (int k = 0; k < 3; ++k) {
        out += scale * Kernel::FT(double(static_cast<std::uint64_t>(u & ((1ULL << 42) - 1))));
        u >>= 42;
        scale *= limb;
    }
    return negative ? -out : out;
}

PolygonSet make_set(const std::vector<Ring>& rings, const std::vector<std::size_t>& which) {
    std::vector<Polygon> polygons;
    polygons.reserve(which.size());
    for (std::size_t i : which) {
        Polygon p;
        for (const PointNm& v : rings[i]) p.push_back(Kernel::Point_2(double(v.x), double(v.y)));
        polygons.push_back(std::move(p));
    }
    PolygonSet set;
    if (!polygons.empty()) set.join(polygons.begin(), polygons.end());
    return set;
}

Kernel::FT area(const PolygonSet& set) {
    std::vector<PolygonWithHoles> parts;
    set.polygons_with_holes(std::back_inserter(parts));
    Kernel::FT total = 0;
    for (const PolygonWithHoles& part : parts) {
        if (part.is_unbounded()) throw RuntimeFailure("area of an unbounded polygon set");
        total += CGAL::abs(part.outer_boundary().area());
        for (auto h = part.holes_begin(); h != part.holes_end(); ++h) total -= CGAL::abs(h->area());
    }
    return total;
}

enum class Op { kXor, kIntersection, kUnion };

// The two index lists name the same multiset of canonical rings (so their unions are equal).
bool same_rings(const std::vector<Ring>& rings, const std::vector<std::size_t>& a,
                const std::vector<std::size_t>& b) {
    if (a.size() != b.size()) return false;
    const auto sorted = [&](const std::vector<std::size_t>& idx) {
        std::vector<const Ring*> out;
        for (std::size_t i : idx) out.push_back(&rings[i]);
        std::sort(out.begin(), out.end(), [](const Ring* p, const Ring* q) {
            return std::lexicographical_compare(p->begin(), p->end(), q->begin(), q->end(),
                                                [](const PointNm& u, const PointNm& v) {
                                                    return u.x != v.x ? u.x < v.x : u.y < v.y;
                                                });
        });
        return out;
    };
    const auto sa = sorted(a), sb = sorted(b);
    for (std::size_t k = 0; k < sa.size(); ++k) {
        if (*sa[k] != *sb[k]) return false;
    }
    return true;
}

// Area of `op` over a and b. Rings whose (closed) bounding boxes are connected form a group;
// regions of different groups are disjoint, so the area is a sum over groups. Groups of one
// ring, of equal ring sets (xor) or of two rectangles are done in integers; the rest in CGAL.
double area_of(const std::vector<Ring>& a, const std::vector<Ring>& b, Op op) {
    std::vector<Ring> rings;
    rings.reserve(a.size() + b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        rings.push_back(canonical(a[i], "a[" + std::to_string(i) + "]"));
    for (std::size_t i = 0; i < b.size(); ++i)
        rings.push_back(canonical(b[i], "b[" + std::to_string(i) + "]"));
    const std::size_t n = rings.size(), n_a = a.size();
    std::vector<std::size_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    const auto root = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::vector<Box> boxes;
    boxes.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        std::int64_t x0 = rings[i][0].x, x1 = x0, y0 = rings[i][0].y, y1 = y0;
        for (const PointNm& p : rings[i]) {
            x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
            y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
        }
        boxes.emplace_back(CGAL::Bbox_2(double(x0), double(y0), double(x1), double(y1)), i);
    }
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& p, const Box& q) {
        parent[root(p.info())] = root(q.info());
    });
    std::vector<std::pair<std::size_t, std::size_t>> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = {root(i), i};
    std::sort(order.begin(), order.end());

    Int128 doubled = 0;  // integer part, twice the area
    Kernel::FT exact = 0;
    std::vector<std::size_t> in_a, in_b;
    for (std::size_t s = 0; s < n;) {
        in_a.clear(), in_b.clear();
        std::size_t e = s;
        for (; e < n && order[e].first == order[s].first; ++e) {
            (order[e].second < n_a ? in_a : in_b).push_back(order[e].second);
        }
        s = e;
        const bool one_each = in_a.size() == 1 && in_b.size() == 1;
        const bool same = one_each && rings[in_a[0]] == rings[in_b[0]];
        if (op == Op::kIntersection) {
            if (in_a.empty() || in_b.empty()) continue;
            if (same) {
                doubled += doubled_area(rings[in_a[0]]);
                continue;
            }
            PolygonSet set = make_set(rings, in_a);
            set.intersection(make_set(rings, in_b));
            exact += area(set);
            continue;
        }
        if (same || (op == Op::kXor && same_rings(rings, in_a, in_b))) continue;  // equal sets
        if (in_a.empty() || in_b.empty()) {  // xor with nothing, or a union: the union's area
            const auto& only = in_a.empty() ? in_b : in_a;
            if (only.size() == 1) {
                doubled += doubled_area(rings[only[0]]);
            } else {
                exact += area(make_set(rings, only));
            }
            continue;
        }
        const auto ba = as_box(rings[in_a[0]]),
                   bb = one_each ? as_box(rings[in_b[0]]) : std::nullopt;
        if (ba && bb) {  // two rectangles: |A| + |B| - 2 |A n B|
            const Int128 w =
                std::max<std::int64_t>(0, std::min(ba->x1, bb->x1) - std::max(ba->x0, bb->x0));
            const Int128 h =
                std::max<std::int64_t>(0, std::min(ba->y1, bb->y1) - std::max(ba->y0, bb->y0));
            doubled += doubled_area(rings[in_a[0]]) + doubled_area(rings[in_b[0]]) - 4 * w * h;
            continue;
        }
        PolygonSet set = make_set(rings, in_a);
        set.symmetric_difference(make_set(rings, in_b));
        exact += area(set);
    }
    return CGAL::to_double(CGAL::exact(exact + to_ft(doubled) / 2));
}

PointNm grid_point(const Kernel::Point_2& p) {
    const auto on_grid = [](const Kernel::FT& v) {
        const std::int64_t n = std::llround(CGAL::to_double(v));
        if (Kernel::FT(static_cast<double>(n)) != v) {
            throw invalid_field("opaque pieces", "a hole vertex near " + std::to_string(n) + " nm",
                                "the clear regions must have vertices on the 1 nm grid");
        }
        return n;
    };
    return {on_grid(p.x()), on_grid(p.y())};
}

}  // namespace

double xor_area_nm2(const std::vector<Ring>& a, const std::vector<Ring>& b) {
    return area_of(a, b, Op::kXor);
}

double intersection_area_nm2(const std::vector<Ring>& a, const std::vector<Ring>& b) {
    return area_of(a, b, Op::kIntersection);
}

double union_area_nm2(const std::vector<Ring>& a) { return area_of(a, {}, Op::kUnion); }

std::vector<Ring> union_holes(const std::vector<Ring>& opaque) {
    std::vector<Ring> rings;
    rings.reserve(opaque.size());
    for (std::size_t i = 0; i < opaque.size(); ++i) {
        rings.push_back(canonical(opaque[i], "opaque[" + std::to_string(i) + "]"));
    }
    std::vector<std::size_t> all(rings.size());
    std::iota(all.begin(), all.end(), 0);
    const PolygonSet set = make_set(rings, all);
    std::vector<PolygonWithHoles> parts;
    set.polygons_with_holes(std::back_inserter(parts));
    std::vector<Ring> out;
    for (const PolygonWithHoles& part : parts) {
        for (auto h = part.holes_begin(); h != part.holes_end(); ++h) {
            Polygon hole = *h;
            if (hole.is_clockwise_oriented()) hole.reverse_orientation();
            Ring ring;
            for (auto v = hole.vertices_begin(); v != hole.vertices_end(); ++v) {
                ring.push_back(grid_point(*v));
            }
            out.push_back(std::move(ring));
        }
    }
    return out;
}

}  // namespace pinmask
