#include "export/xor_area.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>

#include <cmath>
#include <iterator>
#include <string>

#include "core/error.hpp"

namespace pinmask {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Polygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;
using PolygonSet = CGAL::Polygon_set_2<Kernel>;

// The union of `rings` as an exact polygon set; `set_name` names the argument in errors.
PolygonSet make_set(const std::vector<Ring>& rings, const std::string& set_name) {
    std::vector<Polygon> polygons;
    polygons.reserve(rings.size());
    for (std::size_t i = 0; i < rings.size(); ++i) {
        const Ring& ring = rings[i];
        const std::string field = set_name + "[" + std::to_string(i) + "]";
        if (ring.size() < 3) {
            throw invalid_field(field, std::to_string(ring.size()) + " vertices",
                                "a polygon needs at least 3 vertices");
        }
        Polygon p;
        for (const PointNm& v : ring) {
            if (v.x < -kMaxCoordNm || v.x > kMaxCoordNm || v.y < -kMaxCoordNm ||
                v.y > kMaxCoordNm) {
                throw invalid_field(
                    field, std::to_string(v.x) + ", " + std::to_string(v.y),
                    "coordinates must be within +-" + std::to_string(kMaxCoordNm) + " nm");
            }
            // |coordinate| <= 2^30: exactly representable as a double.
            p.push_back(Kernel::Point_2(static_cast<double>(v.x), static_cast<double>(v.y)));
        }
        if (!p.is_simple()) {
            throw invalid_field(field, "a self-intersecting or repeated-vertex ring",
                                "area comparison needs simple polygons");
        }
        if (p.is_clockwise_oriented()) p.reverse_orientation();
        polygons.push_back(std::move(p));
    }
    PolygonSet set;
    if (!polygons.empty()) set.join(polygons.begin(), polygons.end());
    return set;
}

double area_nm2(const PolygonSet& set) {
    std::vector<PolygonWithHoles> parts;
    set.polygons_with_holes(std::back_inserter(parts));
    Kernel::FT total = 0;
    for (const PolygonWithHoles& part : parts) {
        if (part.is_unbounded()) throw RuntimeFailure("area of an unbounded polygon set");
        total += CGAL::abs(part.outer_boundary().area());
        for (auto h = part.holes_begin(); h != part.holes_end(); ++h) total -= CGAL::abs(h->area());
    }
    return CGAL::to_double(CGAL::exact(total));
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
    PolygonSet set = make_set(a, "a");
    set.symmetric_difference(make_set(b, "b"));
    return area_nm2(set);
}

double intersection_area_nm2(const std::vector<Ring>& a, const std::vector<Ring>& b) {
    PolygonSet set = make_set(a, "a");
    set.intersection(make_set(b, "b"));
    return area_nm2(set);
}

double union_area_nm2(const std::vector<Ring>& a) { return area_nm2(make_set(a, "a")); }

std::vector<Ring> union_holes(const std::vector<Ring>& opaque) {
    const PolygonSet set = make_set(opaque, "opaque");
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
