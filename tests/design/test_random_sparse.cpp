// The random sparse family: exact counts, the spacing rule by an independent O(K^2) check,
// determinism, uniform choice among free cells, and fast refusal of infeasible requests.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "core/errors/error.hpp"
#include "design/pattern/exclusion_grid.hpp"
#include "design/pattern/random_sparse.hpp"

using namespace pinmask;
using doctest::Contains;

namespace {

// Pairs at least this close to the spacing count as meeting it (the rule's own tolerance).
constexpr double kRuleTolerance = 1e-9;

// Independent O(K^2) check: K distinct cells inside the grid, every pair (and every pinhole and
// its own periodic copy, n cells away) at least s apart on the torus.
bool satisfies_rule(const Pattern& p, int holes) {
    if (static_cast<int>(p.pinholes.size()) != holes) return false;
    if (p.n < p.min_spacing_cells - kRuleTolerance) return false;
    std::set<std::pair<int, int>> seen;
    for (const Cell& c : p.pinholes) {
        if (c.row < 0 || c.row >= p.n || c.col < 0 || c.col >= p.n) return false;
        if (!seen.insert({c.row, c.col}).second) return false;
    }
    for (std::size_t i = 0; i < p.pinholes.size(); ++i) {
        for (std::size_t j = i + 1; j < p.pinholes.size(); ++j) {
            int dr = std::abs(p.pinholes[i].row - p.pinholes[j].row);
            int dc = std::abs(p.pinholes[i].col - p.pinholes[j].col);
            dr = std::min(dr, p.n - dr);
            dc = std::min(dc, p.n - dc);
            if (std::sqrt(double(dr * dr + dc * dc)) < p.min_spacing_cells - kRuleTolerance) {
                return false;
            }
        }
    }
    return true;
}

Pattern draw(int n, int holes, double s, std::uint64_t seed) {
    RandomSparseOptions o;
    o.n = n;
    o.holes = holes;
    o.min_spacing_cells = s;
    std::mt19937_64 rng(seed);
    return random_sparse_pattern(o, rng);
}

}  // namespace

TEST_CASE("200 seeds x several geometries: K distinct pinholes meeting the rule on the torus") {
    struct Case {
        int n, holes;
        double s;
    };
    // Tiny tori (wrap-around everywhere), odd, prime and power-of-two sizes, non-integer
    // spacings, full packings at s <= 1, and the paper's geometry.
    const Case cases[] = {{16, 20, 2.0},  {1, 1, 0.5},   {2, 4, 1.0},   {3, 1, 2.0},
                          {4, 3, 2.0},    {5, 3, 2.0},   {6, 2, 3.0},   {7, 6, 2.0},
                          {9, 4, 3.0},    {13, 20, 1.5}, {17, 12, 2.5}, {31, 40, 2.0},
                          {64, 300, 2.0}, {12, 144, 0.0}};
    for (const Case& c : cases) {
        for (std::uint64_t seed = 0; seed < 200; ++seed) {
            CAPTURE(c.n);
            CAPTURE(c.holes);
            CAPTURE(c.s);
            CAPTURE(seed);
            const Pattern p = draw(c.n, c.holes, c.s, seed);
            REQUIRE(satisfies_rule(p, c.holes));
            CHECK(spacing_violations(p).empty());
            CHECK(std::is_sorted(p.pinholes.begin(), p.pinholes.end()));
        }
    }
}

TEST_CASE("same seed, same pattern; different seeds, different patterns") {
    CHECK(draw(16, 20, 2.0, 7).pinholes == draw(16, 20, 2.0, 7).pinholes);
    CHECK(draw(101, 500, 2.5, 3).pinholes == draw(101, 500, 2.5, 3).pinholes);
    CHECK(draw(16, 20, 2.0, 7).pinholes != draw(16, 20, 2.0, 8).pinholes);
}

TEST_CASE("a large sparse request and a dense one on a big torus both meet the rule") {
    const Pattern big = draw(4096, 2000, 2.0, 1);
    CHECK(big.pinholes.size() == 2000);
    CHECK(spacing_violations(big).empty());
    // 512^2 / 4 = 65536 fit; random sequential packing stalls near 48900, so 40000 draws from
    // a nearly exhausted free set.
    const Pattern dense = draw(512, 40000, 2.0, 1);
    CHECK(dense.pinholes.size() == 40000);
    CHECK(spacing_violations(dense).empty());
}

TEST_CASE("each pinhole is uniform among the free cells") {
    // K = 1 on 5 x 5: every cell equally likely. 5000 draws, 200 expected per cell, standard
    // deviation ~14: a 5 sigma band.
    constexpr int kDraws = 5000;
    constexpr double kSigmas = 5.0;
    std::map<std::pair<int, int>, int> count;
    for (int seed = 0; seed < kDraws; ++seed) {
        const Cell c = draw(5, 1, 2.0, static_cast<std::uint64_t>(seed)).pinholes[0];
        ++count[{c.row, c.col}];
    }
    CHECK(count.size() == 25);
    const double expected = kDraws / 25.0;
    const double sigma = std::sqrt(expected * (1.0 - 1.0 / 25.0));
    for (const auto& entry : count) {
        const auto& cell = entry.first;
        const auto k = entry.second;
        CAPTURE(cell.first);
        CAPTURE(cell.second);
        CHECK(std::abs(k - expected) <= kSigmas * sigma);
    }
    // K = 2 on 7 x 7 at s = 3.5: a pinhole blocks 37 cells, the second is drawn from the 12
    // left, so each of the 49 * 12 / 2 = 294 valid pairs has probability 1/294.
    constexpr int kPairDraws = 29400;
    std::map<std::vector<Cell>, int> pairs;
    for (int seed = 0; seed < kPairDraws; ++seed) {
        ++pairs[draw(7, 2, 3.5, static_cast<std::uint64_t>(seed)).pinholes];
    }
    CHECK(pairs.size() == 294);
    const double pair_expected = kPairDraws / 294.0;
    const double pair_sigma = std::sqrt(pair_expected);
    for (const auto& [pair, k] : pairs) CHECK(std::abs(k - pair_expected) <= kSigmas * pair_sigma);
}

TEST_CASE("infeasible requests throw with the bound, the lattice count and the random reach") {
    // 80 on 16 x 16 at spacing 2: each 2 x 2 block holds one pinhole, 64 at most.
    CHECK_THROWS_WITH_AS(draw(16, 80, 2.0, 1), Contains("At most 64 fit"), InvalidInput);
    CHECK_THROWS_WITH_AS(draw(16, 80, 2.0, 1), Contains("lattice placement holds 64"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(draw(16, 80, 2.0, 1), Contains("random sequential placement reached"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(draw(16, 65, 2.0, 1), Contains("`holes` = 65"), InvalidInput);
    // 64 is the exact maximum, but random sequential choice jams long before it.
    CHECK_THROWS_WITH_AS(draw(16, 64, 2.0, 1), Contains("(best of 20 attempts)"), InvalidInput);
    // Odd torus: floor(5 * 2 / 2) = 5 at most.
    CHECK_THROWS_WITH_AS(draw(5, 6, 2.0, 1), Contains("At most 5 fit"), InvalidInput);
    // Spacing beyond the torus: nothing fits.
    CHECK_THROWS_WITH_AS(draw(3, 1, 4.0, 1), Contains("At most 0 fit"), InvalidInput);
    // A huge torus asked for more than fit is refused by the bound before any long search.
    CHECK_THROWS_WITH_AS(draw(1024, 1024 * 1024 / 4 + 1, 2.0, 1), Contains("At most 262144 fit"),
                         InvalidInput);
}

TEST_CASE("options are validated") {
    CHECK_THROWS_AS(draw(0, 1, 2.0, 1), InvalidInput);
    CHECK_THROWS_AS(draw(5000, 1, 2.0, 1), InvalidInput);
    CHECK_THROWS_AS(draw(16, 0, 2.0, 1), InvalidInput);
    CHECK_THROWS_AS(draw(16, 4, -1.0, 1), InvalidInput);
    CHECK_THROWS_AS(draw(16, 4, INFINITY, 1), InvalidInput);
    RandomSparseOptions o;
    o.tiles_rows = 0;
    std::mt19937_64 rng(1);
    CHECK_THROWS_AS(random_sparse_pattern(o, rng), InvalidInput);
}

TEST_CASE("exclusion grid: rank index finds the r-th free cell, blocks wrap the seams") {
    for (const int n : {1, 2, 7, 8, 13, 64}) {
        ExclusionGrid g(n, 2.0, ExclusionGrid::Index::kRank);
        g.place({0, 0});
        if (n > 3) g.place({n / 2, n / 2});
        std::vector<std::size_t> free_cells;
        for (std::size_t i = 0; i < static_cast<std::size_t>(n) * n; ++i) {
            if (g.is_free(i)) free_cells.push_back(i);
        }
        CAPTURE(n);
        REQUIRE(free_cells.size() == g.free_count());
        for (std::size_t r = 0; r < free_cells.size(); ++r) CHECK(g.nth_free(r) == free_cells[r]);
        if (n >= 3) {
            // The corner pinhole blocks its 8 neighbours through the seams.
            CHECK_FALSE(g.is_free(Cell{n - 1, n - 1}));
            CHECK_FALSE(g.is_free(Cell{0, n - 1}));
            CHECK_FALSE(g.is_free(Cell{n - 1, 1}));
        }
    }
}

TEST_CASE("exclusion grid: a pinhole blocks exactly the cells closer than the rule, seams too") {
    for (const int n : {1, 2, 3, 5, 8, 13}) {
        for (const double s : {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, std::sqrt(8.0), 3.2, 5.0, 13.0}) {
            if (n < s - kRuleTolerance) continue;  // refused before a grid is built
            for (const Cell c : {Cell{0, 0}, Cell{n - 1, n / 2}}) {
                ExclusionGrid g(n, s);
                g.place(c);
                CAPTURE(n);
                CAPTURE(s);
                std::size_t blocked = 0;
                for (int r = 0; r < n; ++r) {
                    for (int k = 0; k < n; ++k) {
                        int dr = std::abs(r - c.row);
                        int dc = std::abs(k - c.col);
                        dr = std::min(dr, n - dr);
                        dc = std::min(dc, n - dc);
                        const bool close =
                            std::sqrt(double(dr * dr + dc * dc)) < s - kRuleTolerance ||
                            (dr == 0 && dc == 0);
                        CHECK(g.is_free(Cell{r, k}) == !close);
                        blocked += close;
                    }
                }
                CHECK(g.free_count() == static_cast<std::size_t>(n) * n - blocked);
            }
        }
    }
}
