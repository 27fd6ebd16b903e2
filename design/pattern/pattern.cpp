#include "design/pattern/pattern.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

int torus_delta(int a, int b, int n) {
    const int d = std::abs(a - b) % n;
    return std::min(d, n - d);
}

std::string cell_text(Cell c) {
    return "(" + std::to_string(c.row) + ", " + std::to_string(c.col) + ")";
}

}  // namespace

double torus_distance_cells(Cell a, Cell b, int n) {
    const double dr = torus_delta(a.row, b.row, n);
    const double dc = torus_delta(a.col, b.col, n);
    return std::sqrt(dr * dr + dc * dc);
}

std::vector<SpacingViolation> spacing_violations(const Pattern& p) {
    std::vector<SpacingViolation> out;
    const int n = p.n;
    const double s = p.min_spacing_cells;
    if (p.pinholes.empty() || s <= 0.0) return out;
    // A pinhole's nearest periodic copy is n cells away (the mask is cyclic even untiled, since
    // the PSF is a torus): too close when n < s.
    if (n < s - kSpacingTolerance) {
        for (const Cell& c : p.pinholes) out.push_back({c, c, static_cast<double>(n)});
    }
    const int reach = std::min(static_cast<int>(std::ceil(s)), n / 2);
    const auto occ = occupancy(p);
    for (const Cell& a : p.pinholes) {
        for (int dr = -reach; dr <= reach; ++dr) {
            for (int dc = -reach; dc <= reach; ++dc) {
                if (dr == 0 && dc == 0) continue;
                const Cell b{((a.row + dr) % n + n) % n, ((a.col + dc) % n + n) % n};
                if (!(a < b) || occ[static_cast<std::size_t>(b.row) * n + b.col] == 0) continue;
                const double d = torus_distance_cells(a, b, n);
                // Wrapped offsets can reach the same cell twice on small tori; the (a < b) and
                // exact-offset test keep each pair once.
                if (std::abs(d * d - (dr * dr + dc * dc)) > 1e-9) continue;
                if (d < s - kSpacingTolerance) out.push_back({a, b, d});
            }
        }
    }
    // On even tori the offsets +n/2 and -n/2 reach the same cell: keep each pair once.
    std::sort(out.begin(), out.end(), [](const SpacingViolation& x, const SpacingViolation& y) {
        return std::tie(x.a, x.b) < std::tie(y.a, y.b);
    });
    out.erase(std::unique(out.begin(), out.end(),
                          [](const SpacingViolation& x, const SpacingViolation& y) {
                              return x.a == y.a && x.b == y.b;
                          }),
              out.end());
    return out;
}

void validate(const Pattern& p, bool allow_spacing_violations) {
    if (p.n < 1 || p.n > kMaxGrid) {
        throw invalid_field("pattern.n", std::to_string(p.n),
                            "must be between 1 and " + std::to_string(kMaxGrid));
    }
    if (p.tiles_rows < 1 || p.tiles_cols < 1 || p.tiles_rows > kMaxTiles ||
        p.tiles_cols > kMaxTiles) {
        throw invalid_field("pattern.tiles",
                            std::to_string(p.tiles_rows) + "x" + std::to_string(p.tiles_cols),
                            "both must be between 1 and " + std::to_string(kMaxTiles) +
                                " (kMaxTiles: export cannot lay out more periods)");
    }
    if (!std::isfinite(p.min_spacing_cells) || p.min_spacing_cells < 0.0) {
        throw invalid_field("pattern.min_spacing_cells", std::to_string(p.min_spacing_cells),
                            "must be finite and >= 0");
    }
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(p.n) * p.n, 0);
    for (std::size_t i = 0; i < p.pinholes.size(); ++i) {
        const Cell c = p.pinholes[i];
        if (c.row < 0 || c.row >= p.n || c.col < 0 || c.col >= p.n) {
            throw invalid_field(
                "pattern.pinholes[" + std::to_string(i) + "]", cell_text(c),
                "outside the " + std::to_string(p.n) + " x " + std::to_string(p.n) + " grid");
        }
        auto& s = seen[static_cast<std::size_t>(c.row) * p.n + c.col];
        if (s) {
            throw invalid_field("pattern.pinholes[" + std::to_string(i) + "]", cell_text(c),
                                "duplicate pinhole");
        }
        s = 1;
    }
    if (!allow_spacing_violations) {
        const auto v = spacing_violations(p);
        if (!v.empty()) {
            std::ostringstream msg;
            msg << v.size() << " pair(s) closer than " << p.min_spacing_cells
                << " cells on the torus, first " << cell_text(v[0].a) << " - " << cell_text(v[0].b)
                << " at " << v[0].distance_cells << " cells";
            throw invalid_field("pattern.min_spacing_cells", std::to_string(p.min_spacing_cells),
                                msg.str());
        }
    }
}

std::vector<std::uint8_t> occupancy(const Pattern& p) {
    std::vector<std::uint8_t> occ(static_cast<std::size_t>(p.n) * p.n, 0);
    for (const Cell& c : p.pinholes) occ[static_cast<std::size_t>(c.row) * p.n + c.col] = 1;
    return occ;
}

std::vector<Cell> sorted_pinholes(const Pattern& p) {
    std::vector<Cell> v = p.pinholes;
    std::sort(v.begin(), v.end());
    return v;
}

}  // namespace pinmask
