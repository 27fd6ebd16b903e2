// Packing bounds on the torus against the exact maximum found by exhaustive search on tiny tori.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/errors/error.hpp"
#include "design/pattern/packing_bound.hpp"

using namespace pinmask;

namespace {

// Pairs at least this close to the spacing count as meeting it (the rule's own tolerance).
constexpr double kRuleTolerance = 1e-9;

// Test-local torus distance (independent of design/pattern/pattern.cpp).
double torus_dist(int r1, int c1, int r2, int c2, int n) {
    int dr = std::abs(r1 - r2);
    int dc = std::abs(c1 - c2);
    dr = std::min(dr, n - dr);
    dc = std::min(dc, n - dc);
    return std::sqrt(static_cast<double>(dr * dr + dc * dc));
}

struct Graph {
    int v = 0;
    std::vector<std::uint64_t> nb;  // conflict neighbours (n^2 <= 64)
};

Graph conflict_graph(int n, double s) {
    Graph g;
    g.v = n * n;
    g.nb.assign(static_cast<std::size_t>(g.v), 0);
    for (int a = 0; a < g.v; ++a) {
        for (int b = 0; b < g.v; ++b) {
            if (a != b && torus_dist(a / n, a % n, b / n, b % n, n) < s - kRuleTolerance) {
                g.nb[a] |= std::uint64_t{1} << b;
            }
        }
    }
    return g;
}

void search(const Graph& g, std::uint64_t cand, int cur, int& best) {
    if (cur + std::popcount(cand) <= best) return;
    if (cand == 0) {
        best = cur;
        return;
    }
    const int v = std::countr_zero(cand);
    const std::uint64_t bit = std::uint64_t{1} << v;
    search(g, cand & ~bit & ~g.nb[v], cur + 1, best);
    if (g.nb[v] & cand) search(g, cand & ~bit, cur, best);
}

// Exact maximum number of pinholes on the n x n torus (n^2 <= 64) by branch and bound.
int exact_maximum(int n, double s) {
    if (n < s - kRuleTolerance) return 0;  // each pinhole clashes with its own copy
    const Graph g = conflict_graph(n, s);
    // The torus is vertex-transitive: some optimum contains cell 0.
    const std::uint64_t all = g.v == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << g.v) - 1;
    int best = 0;
    search(g, all & ~std::uint64_t{1} & ~g.nb[0], 1, best);
    return best;
}

bool placement_valid(const std::vector<Cell>& cells, int n, double s) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
        for (std::size_t j = i + 1; j < cells.size(); ++j) {
            if (torus_dist(cells[i].row, cells[i].col, cells[j].row, cells[j].col, n) <
                s - kRuleTolerance) {
                return false;
            }
        }
    }
    return true;
}

}  // namespace

TEST_CASE("upper bound >= exact maximum >= verified lattice placement on tiny tori") {
    const double spacings[] = {0.0, 0.5, 1.0, 1.2, 1.5, 2.0, 2.2, std::sqrt(5.0),
                               2.5, 3.0, 3.5, 4.0, 5.0};
    for (int n = 1; n <= 7; ++n) {
        for (const double s : spacings) {
            CAPTURE(n);
            CAPTURE(s);
            const int exact = exact_maximum(n, s);
            const auto upper = packing_upper_bound(n, s);
            const auto lattice = lattice_placement(n, s);
            CHECK(upper.count >= exact);
            CHECK(static_cast<int>(lattice.cells.size()) <= exact);
            CHECK(placement_valid(lattice.cells, n, s));
            CHECK_FALSE(upper.reason.empty());
            if (s <= 1.0 && n >= s) {
                CHECK(upper.count == n * n);  // no constraint between distinct cells
                CHECK(static_cast<int>(lattice.cells.size()) == n * n);
            }
            if (n < s) CHECK(upper.count == 0);
        }
    }
}

TEST_CASE("spacing 2: the strip bound is exact for every n (Hales: floor(n floor(n/2) / 2))") {
    for (int n = 2; n <= 7; ++n) {
        CAPTURE(n);
        const int exact = exact_maximum(n, 2.0);
        CHECK(exact == n * (n / 2) / 2);
        CHECK(packing_upper_bound(n, 2.0).count == exact);
        // Even tori: the 2 x 2 lattice reaches it.
        if (n % 2 == 0) CHECK(static_cast<int>(lattice_placement(n, 2.0).cells.size()) == exact);
    }
    // Larger tori, beyond exhaustive search: (n/2)^2 for even n, the lattice meets it.
    for (const int n : {16, 32, 64, 128}) {
        CAPTURE(n);
        CHECK(packing_upper_bound(n, 2.0).count == (n / 2) * (n / 2));
        CHECK(static_cast<long long>(lattice_placement(n, 2.0).cells.size()) == (n / 2) * (n / 2));
    }
}

TEST_CASE("large spacings use the disk-packing bound; prime and odd sizes stay consistent") {
    // s = 10 on 64 x 64: the best strip (a = 8 rows, columns >= 8 apart) gives 64 * 8 / 8 = 64,
    // the disk bound floor(2 * 64^2 / (sqrt(3) * 10^2)) = floor(47.3) = 47.
    const auto b = packing_upper_bound(64, 10.0);
    CHECK(b.count == 47);
    CHECK(b.reason.find("Thue") != std::string::npos);
    // s = 3 on 16 x 16: strips of a = 3 rows, columns >= 3 apart: 16 * 5 / 3 = 26; the disk
    // bound is 32. The 3 x 3 lattice holds 25 (rows 0..12, the seam gap is 4).
    CHECK(packing_upper_bound(16, 3.0).count == 26);
    CHECK(lattice_placement(16, 3.0).cells.size() == 25);
    for (const int n : {17, 31, 32, 33}) {
        for (const double s : {1.5, 2.0, 3.0, 4.5}) {
            CAPTURE(n);
            CAPTURE(s);
            const auto lattice = lattice_placement(n, s);
            CHECK(static_cast<long long>(lattice.cells.size()) <= packing_upper_bound(n, s).count);
            CHECK(placement_valid(lattice.cells, n, s));
            CHECK(lattice.cells.size() > 0);
        }
    }
}

TEST_CASE("bound arguments are validated") {
    CHECK_THROWS_AS(packing_upper_bound(0, 2.0), InvalidInput);
    CHECK_THROWS_AS(packing_upper_bound(16, -1.0), InvalidInput);
    CHECK_THROWS_AS(packing_upper_bound(16, NAN), InvalidInput);
    CHECK_THROWS_AS(lattice_placement(5000, 2.0), InvalidInput);
}
