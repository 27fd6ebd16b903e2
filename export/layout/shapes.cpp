#include "export/layout/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/errors/error.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {

std::int64_t snap_nm(double v_nm, std::int64_t grid_nm) {
    return std::llround(v_nm / static_cast<double>(grid_nm)) * grid_nm;
}

std::int64_t floor_to_grid(double v_nm, std::int64_t grid_nm) {
    return static_cast<std::int64_t>(std::floor(v_nm / static_cast<double>(grid_nm))) * grid_nm;
}

std::int64_t ceil_to_grid(double v_nm, std::int64_t grid_nm) {
    return static_cast<std::int64_t>(std::ceil(v_nm / static_cast<double>(grid_nm))) * grid_nm;
}

std::string nm_text(double nm) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g nm", nm);
    return buf;
}

double sagitta_nm(double radius_nm, int sides) {
    return radius_nm * (1.0 - std::cos(std::numbers::pi / sides));
}

int sides_for_chord_tolerance(double radius_nm, double tolerance_nm) {
    if (!(radius_nm > 0) || !std::isfinite(radius_nm))
        throw invalid_field("hole radius", nm_text(radius_nm), "must be positive and finite");
    if (!(tolerance_nm > 0) || !std::isfinite(tolerance_nm))
        throw invalid_field("chord_tolerance", nm_text(tolerance_nm),
                            "must be positive and finite");
    // 1 - cos(pi/N) = 2 sin^2(pi/(2N)) <= t/r  <=>  N >= pi / (2 asin(sqrt(t / (2r)))).
    const double ratio = tolerance_nm / (2.0 * radius_nm);
    double n_min = 8.0;
    if (ratio < 1.0) n_min = std::max(8.0, std::numbers::pi / (2.0 * std::asin(std::sqrt(ratio))));
    if (n_min > kMaxPolygonSides)
        throw invalid_field("chord_tolerance", nm_text(tolerance_nm),
                            "needs more than " + std::to_string(kMaxPolygonSides) +
                                " sides for a hole of radius " + std::to_string(radius_nm) +
                                " nm; use a larger tolerance");
    int n = 4 * static_cast<int>(std::ceil(n_min / 4.0 - 1e-12));
    while (sagitta_nm(radius_nm, n) > tolerance_nm) n += 4;  // guards the rounding of asin
    while (n > 8 && sagitta_nm(radius_nm, n - 4) <= tolerance_nm) n -= 4;
    return n;
}

int circle_sides(double radius_nm, double tolerance_nm, std::size_t max_vertices,
                 std::int64_t grid_nm) {
    const int cap = 4 * static_cast<int>(
                            std::min<std::size_t>(max_vertices, std::size_t(kMaxPolygonSides)) / 4);
    if (cap < 8)
        throw invalid_field("max_vertices", std::to_string(max_vertices),
                            "must be >= 8 for circles");
    if (tolerance_nm == 0.0) {
        int n = cap;
        while (n > 8 && sagitta_nm(radius_nm, n - 4) <= double(grid_nm)) n -= 4;
        return n;
    }
    const int n = sides_for_chord_tolerance(radius_nm, tolerance_nm);
    if (n > cap) {
        throw invalid_field("chord_tolerance", nm_text(tolerance_nm),
                            "needs " + std::to_string(n) + " vertices per circle, more than the " +
                                std::to_string(max_vertices) +
                                " allowed (max_vertices); the "
                                "finest tolerance within them is " +
                                nm_text(std::ceil(sagitta_nm(radius_nm, cap))));
    }
    return n;
}

bool is_strictly_convex_ccw(const Ring& ring) {
    const std::size_t n = ring.size();
    if (n < 3) return false;
    for (std::size_t i = 0; i < n; ++i) {
        const PointNm& a = ring[i];
        const PointNm& b = ring[(i + 1) % n];
        const PointNm& c = ring[(i + 2) % n];
        const WideInt turn = WideInt(b.x - a.x) * (c.y - b.y) - WideInt(b.y - a.y) * (c.x - b.x);
        if (turn <= 0) return false;
    }
    // Left turns everywhere and a total turning of one revolution: positive area excludes the
    // star polygons that also turn left at every vertex.
    return doubled_area(ring) > 0;
}

std::vector<std::pair<double, double>> regular_polygon_offsets(double radius_nm, int sides) {
    if (sides < 3)
        throw invalid_field("sides", std::to_string(sides), "a polygon needs at least 3 sides");
    std::vector<std::pair<double, double>> out;
    out.reserve(static_cast<std::size_t>(sides));
    for (int k = 0; k < sides; ++k) {
        const double a = (2.0 * k + 1.0) * std::numbers::pi / sides;
        out.push_back({radius_nm * std::cos(a), radius_nm * std::sin(a)});
    }
    return out;
}

Ring place_polygon(const std::vector<std::pair<double, double>>& offsets, double cx_nm,
                   double cy_nm, const BoxNm& cell, std::int64_t grid_nm) {
    auto toward = [&](double v, double c, std::int64_t lo, std::int64_t hi) {
        const std::int64_t s = v >= c ? floor_to_grid(v, grid_nm) : ceil_to_grid(v, grid_nm);
        return std::clamp(s, lo + grid_nm, hi - grid_nm);
    };
    Ring ring;
    ring.reserve(offsets.size());
    for (const auto& [dx, dy] : offsets)
        ring.push_back({toward(cx_nm + dx, cx_nm, cell.x0, cell.x1),
                        toward(cy_nm + dy, cy_nm, cell.y0, cell.y1)});
    ring = simplified(std::move(ring));
    if (!is_strictly_convex_ccw(ring))
        throw invalid_field("grid", std::to_string(grid_nm) + " nm",
                            "too coarse for a " + std::to_string(offsets.size()) +
                                "-gon of this size: the snapped polygon is not convex; use a "
                                "finer grid or a larger chord tolerance");
    return ring;
}

Ring regular_polygon(double cx_nm, double cy_nm, double radius_nm, int sides, const BoxNm& cell,
                     std::int64_t grid_nm) {
    return place_polygon(regular_polygon_offsets(radius_nm, sides), cx_nm, cy_nm, cell, grid_nm);
}

}  // namespace pinmask
