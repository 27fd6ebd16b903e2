#include "design/optics/fab_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <utility>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

// 2^30 nm (about 1.07 m): the coordinate bound of the layouts (export/layout/xor_area kMaxCoordNm).
constexpr double kMaxPitchNm = 1073741824.0;

int torus_delta(int a, int b, int n) {
    const int d = std::abs(a - b) % n;
    return std::min(d, n - d);
}

std::string nm_plain(double nm) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6g nm", nm);
    return buf;
}

}  // namespace

std::string um_text(double nm) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.3f um", nm * 1e-3);
    return buf;
}

std::int64_t fab_grid_nm(double grid_m, const std::string& field) {
    const double nm = grid_m * 1e9;
    const double whole = std::round(nm);
    if (!std::isfinite(nm) || whole < 1 || whole > 1e6 || std::fabs(nm - whole) > 1e-6)
        throw invalid_field(field, nm_plain(nm),
                            "must be a whole number of nm between 1 nm and 1 mm");
    return static_cast<std::int64_t>(whole);
}

std::int64_t pitch_on_grid_nm(double pinhole_m, std::int64_t grid_nm) {
    const double nm = pinhole_m * 1e9;
    if (!std::isfinite(nm) || !(nm > 0) || nm > kMaxPitchNm)
        throw invalid_field("pinhole_m", nm_plain(nm), "must be finite, > 0 and at most 2^30 nm");
    if (grid_nm < 1) throw invalid_field("grid_nm", std::to_string(grid_nm), "must be >= 1");
    const double steps = std::max(1.0, std::round(nm / double(grid_nm)));
    return static_cast<std::int64_t>(steps) * grid_nm;
}

double pinhole_on_grid_m(double pinhole_m, std::int64_t grid_nm) {
    return double(pitch_on_grid_nm(pinhole_m, grid_nm)) * 1e-9;
}

GridSpacing spacing_on_grid(const Pattern& p, double pinhole_m, std::int64_t grid_nm) {
    GridSpacing g;
    g.grid_nm = grid_nm;
    g.pitch_nm = pitch_on_grid_nm(pinhole_m, grid_nm);
    const double pitch = double(g.pitch_nm);
    g.limit_nm = p.min_spacing_cells * pitch;
    g.closest_nm = std::numeric_limits<double>::infinity();
    const int n = p.n;
    if (p.pinholes.empty() || n < 1) return g;
    const double limit = g.limit_nm - kCentroidToleranceNm;
    auto consider = [&](Cell a, Cell b, double distance_nm) {
        if (distance_nm < g.closest_nm) {
            g.closest_nm = distance_nm;
            g.closest_a = a;
            g.closest_b = b;
        }
        if (distance_nm < limit) ++g.violations;
    };
    // A pinhole's nearest periodic copy is n cells away (the mask is cyclic).
    if (double(n) * pitch < limit)
        for (const Cell& c : p.pinholes) consider(c, c, double(n) * pitch);
    const int reach =
        std::min(static_cast<int>(std::ceil(std::max(p.min_spacing_cells, 1.0))), n / 2);
    const auto occ = occupancy(p);
    std::set<std::pair<Cell, Cell>> seen;
    for (const Cell& a : p.pinholes) {
        for (int dr = -reach; dr <= reach; ++dr) {
            for (int dc = -reach; dc <= reach; ++dc) {
                if (dr == 0 && dc == 0) continue;
                const Cell b{((a.row + dr) % n + n) % n, ((a.col + dc) % n + n) % n};
                if (!(a < b) || occ[static_cast<std::size_t>(b.row) * n + b.col] == 0) continue;
                if (!seen.insert({a, b}).second) continue;  // reached twice on a small torus
                const long long tr = torus_delta(a.row, b.row, n);
                const long long tc = torus_delta(a.col, b.col, n);
                consider(a, b, std::sqrt(double(tr * tr + tc * tc)) * pitch);
            }
        }
    }
    return g;
}

std::string spacing_rule_text(double min_spacing_cells, std::int64_t pitch_nm,
                              std::int64_t grid_nm) {
    if (!(min_spacing_cells > 0))
        return "no pinhole spacing rule (pitch " + um_text(double(pitch_nm)) + " on the " +
               std::to_string(grid_nm) + " nm grid)";
    char cells[32];
    std::snprintf(cells, sizeof cells, "%.9g", min_spacing_cells);
    return "pinhole centres >= " + um_text(min_spacing_cells * double(pitch_nm)) + " (" + cells +
           " x pitch " + um_text(double(pitch_nm)) + " on the " + std::to_string(grid_nm) +
           " nm grid)";
}

}  // namespace pinmask
