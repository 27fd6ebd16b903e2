#include "design/pattern/packing_bound.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "design/pattern/exclusion_grid.hpp"

namespace pinmask {
namespace {

// Guards floor() of the disk bound against rounding just below an integer: the bound must not
// shrink by one through floating-point error.
constexpr double kFloorGuard = 1e-9;

void check_arguments(int n, double s) {
    if (n < 1 || n > kMaxGrid) {
        throw invalid_field("n", std::to_string(n),
                            "must be between 1 and " + std::to_string(kMaxGrid));
    }
    if (!std::isfinite(s) || s < 0.0) {
        throw invalid_field("min_spacing_cells", std::to_string(s), "must be finite and >= 0");
    }
}

struct Lattice {
    int p = 1;  // row step
    int q = 1;  // column step
    int t = 0;  // column shift per row step
    long long expected = 0;
};

// True when no nonzero vector i (p, t) + j (0, q) of the infinite lattice is shorter than the
// rule (squared length < limit2). Only vectors with |row|, |col| <= reach can be that short.
bool lattice_meets_rule(const Lattice& l, double limit2, int reach) {
    for (int i = -reach / l.p; i <= reach / l.p; ++i) {
        const long long row = static_cast<long long>(i) * l.p;
        const long long base = static_cast<long long>(i) * l.t;
        // j with |base + j q| <= reach.
        const long long j_lo = (-reach - base) / l.q - 1;
        const long long j_hi = (reach - base) / l.q + 1;
        for (long long j = j_lo; j <= j_hi; ++j) {
            const long long col = base + j * l.q;
            if (i == 0 && j == 0) continue;
            if (static_cast<double>(row * row + col * col) < limit2) return false;
        }
    }
    return true;
}

}  // namespace

PackingUpperBound packing_upper_bound(int n, double s) {
    check_arguments(n, s);
    const double limit = s - kSpacingTolerance;  // valid pairs are at least this far apart
    const long long nn = static_cast<long long>(n) * n;
    if (n < limit) {
        return {0, "the spacing " + std::to_string(s) +
                       " exceeds the torus size n = " + std::to_string(n) +
                       ": every pinhole is closer than that to its own periodic copy"};
    }
    PackingUpperBound best{nn, "one pinhole per cell: K <= n^2 = " + std::to_string(nn)};
    if (!(limit > 1.0)) return best;  // distinct cells are >= 1 apart: nothing tighter
    const double limit2 = limit * limit;

    for (int a = 1; a <= n && static_cast<double>(a - 1) * (a - 1) < limit2; ++a) {
        const double rows2 = static_cast<double>(a - 1) * (a - 1);
        int g = static_cast<int>(std::floor(std::sqrt(limit2 - rows2)));
        while (g > 0 && rows2 + static_cast<double>(g - 1) * (g - 1) >= limit2) --g;
        while (rows2 + static_cast<double>(g) * g < limit2) ++g;
        const long long per_band = std::max(1, n / g);
        const long long bound = static_cast<long long>(n) * per_band / a;
        if (bound < best.count) {
            std::ostringstream why;
            why << "a band of " << a << " consecutive row(s) holds at most " << per_band
                << " pinholes (their columns must be >= " << g << " apart on the " << n
                << "-cycle) and each row lies in " << a << " bands: K <= " << n << " * " << per_band
                << " / " << a << " = " << bound;
            best = {bound, why.str()};
        }
    }

    const double disk = 2.0 * static_cast<double>(nn) / (std::sqrt(3.0) * limit2);
    const auto disk_bound = static_cast<long long>(std::floor(disk * (1.0 + kFloorGuard)));
    if (disk_bound < best.count) {
        std::ostringstream why;
        why << "disks of diameter s around the pinholes are disjoint and cannot cover more than "
               "pi/sqrt(12) of the torus (Thue): K <= 2 n^2 / (sqrt(3) s^2) = "
            << disk_bound;
        best = {disk_bound, why.str()};
    }
    return best;
}

LatticePlacement lattice_placement(int n, double s) {
    check_arguments(n, s);
    const double limit = s - kSpacingTolerance;
    if (n < limit) return {{}, "none: the spacing exceeds the torus size"};
    check_memory(9.0 * n * n, "lattice placement on a " + std::to_string(n) + " x " +
                                  std::to_string(n) + " torus");
    const double limit2 = limit > 0.0 ? limit * limit : 0.0;
    const int reach = std::max(1, static_cast<int>(std::ceil(limit)));

    // The column step q must be >= s (the vector (0, q)); a lattice with p q > reach^2 is
    // sparser than the rectangular reach x reach one, which always meets the rule. Small
    // spacings try every such (p, q, t); large ones only rectangular and half-shifted rows.
    constexpr int kFullSearchReach = 12;
    std::vector<Lattice> candidates;
    const long long max_det = static_cast<long long>(reach) * reach;
    for (int p = 1; p <= std::min(reach, n); ++p) {
        const long long q_max = reach <= kFullSearchReach ? max_det / p : reach;
        for (long long q = reach; q <= std::min<long long>(q_max, n); ++q) {
            std::vector<long long> shifts;
            if (reach <= kFullSearchReach) {
                for (long long t = 0; t < q; ++t) shifts.push_back(t);
            } else {
                shifts = {0, q / 2};
            }
            for (const long long t : shifts) {
                Lattice l{p, static_cast<int>(q), static_cast<int>(t),
                          static_cast<long long>(n / p) * (n / q)};
                if (lattice_meets_rule(l, limit2, reach)) candidates.push_back(l);
            }
        }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Lattice& a, const Lattice& b) {
        return std::tie(b.expected, a.p, a.q, a.t) < std::tie(a.expected, b.p, b.q, b.t);
    });
    // The densest few lattices are built; the seams may cost some of their points.
    constexpr std::size_t kLatticesTried = 5;
    if (candidates.size() > kLatticesTried) candidates.resize(kLatticesTried);

    LatticePlacement best;
    for (const Lattice& l : candidates) {
        ExclusionGrid grid(n, s);
        std::vector<Cell> cells;
        const int rows = n / l.p;
        const int cols = n / l.q;
        for (int i = 0; i < rows; ++i) {
            for (int j = 0; j < cols; ++j) {
                const Cell c{i * l.p, static_cast<int>((static_cast<long long>(i) * l.t +
                                                        static_cast<long long>(j) * l.q) %
                                                       n)};
                if (!grid.is_free(c)) continue;
                grid.place(c);
                cells.push_back(c);
            }
        }
        if (cells.size() > best.cells.size() || best.description.empty()) {
            std::ostringstream d;
            d << "rows every " << l.p << ", columns every " << l.q << ", shift " << l.t
              << " per row step: " << rows << " x " << cols << " points, "
              << static_cast<long long>(rows) * cols - static_cast<long long>(cells.size())
              << " dropped at the seams";
            best = {std::move(cells), d.str()};
        }
        // Candidates are sorted by size before the seams: none after a loss-free one can win.
        if (static_cast<long long>(best.cells.size()) >= l.expected) break;
    }
    Pattern check;
    check.n = n;
    check.min_spacing_cells = s;
    check.pinholes = best.cells;
    if (!spacing_violations(check).empty()) {
        throw RuntimeFailure("internal error: lattice placement (" + best.description +
                             ") breaks the spacing rule");
    }
    return best;
}

}  // namespace pinmask
