#include <doctest/doctest.h>

#include <random>

#include "design/pattern/pattern.hpp"
#include "design/psf/psf.hpp"
#include "optimize/search/pattern_state.hpp"

using namespace pinmask;

namespace {

// 10^4 rank-one updates of unit-modulus terms: round-off grows like sqrt(moves) * K * eps; 1e-9
// absolute leaves three orders of magnitude of margin for K <= 100.
constexpr double kIncrementalSpectrumTol = 1e-9;

// A deterministic legal starting pattern: pinholes on a lattice of step `step`.
Pattern lattice_pattern(int n, int holes, int step, double spacing) {
    Pattern p;
    p.n = n;
    p.min_spacing_cells = spacing;
    for (int r = 0; r + step <= n && static_cast<int>(p.pinholes.size()) < holes; r += step)
        for (int c = 0; c + step <= n && static_cast<int>(p.pinholes.size()) < holes; c += step)
            p.pinholes.push_back({r, c});
    return p;
}

// Independent legality check: brute-force torus distances to every other pinhole.
bool brute_force_legal(const Pattern& p, int j, Cell to) {
    if (p.pinholes[j] == to) return false;  // staying put is not a move
    for (int i = 0; i < static_cast<int>(p.pinholes.size()); ++i) {
        if (i == j) continue;
        if (p.pinholes[i] == to) return false;
        if (torus_distance_cells(p.pinholes[i], to, p.n) < p.min_spacing_cells - kSpacingTolerance)
            return false;
    }
    return true;
}

// Independent reference: R(d) by counting ordered pairs, O(K^2).
std::vector<int> direct_autocorrelation(const Pattern& p) {
    const int n = p.n;
    std::vector<int> r(static_cast<std::size_t>(n) * n, 0);
    for (const Cell& a : p.pinholes)
        for (const Cell& b : p.pinholes)
            ++r[static_cast<std::size_t>((b.row - a.row + n) % n) * n + (b.col - a.col + n) % n];
    return r;
}

void run_random_moves(int n, int holes, int step, double spacing, int moves, unsigned seed) {
    PatternState state(lattice_pattern(n, holes, step, spacing));
    REQUIRE(state.holes() == holes);
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> pick_hole(0, holes - 1), pick_cell(0, n - 1);
    int accepted = 0;
    for (int m = 0; m < moves; ++m) {
        const int j = pick_hole(rng);
        const Cell to{pick_cell(rng), pick_cell(rng)};
        const bool legal = state.is_legal_move(j, to);
        REQUIRE(legal == brute_force_legal(state.pattern(), j, to));
        if (legal) {
            state.move(j, to);
            ++accepted;
        }
    }
    INFO("n " << n << ", K " << holes << ", accepted " << accepted << " of " << moves);
    CHECK(accepted > moves / 20);
    CHECK(spacing_violations(state.pattern()).empty());
    const ComplexPlane full = pattern_spectrum(state.pattern());
    CHECK((state.spectrum() - full).abs().maxCoeff() <= kIncrementalSpectrumTol);
    CHECK(state.autocorrelation() == direct_autocorrelation(state.pattern()));
}

}  // namespace

TEST_CASE("incremental spectrum and autocorrelation equal full recomputation after 10^4 moves") {
    run_random_moves(16, 20, 2, 2.0, 10000, 1);   // the paper's geometry
    run_random_moves(17, 12, 3, 2.5, 10000, 2);   // odd (prime) n, real-valued spacing
    run_random_moves(64, 100, 4, 2.0, 10000, 3);  // larger torus
    run_random_moves(5, 3, 2, 1.0, 10000, 4);     // tiny torus: wrap-around everywhere
}

TEST_CASE("moves across the seam respect the torus spacing rule") {
    Pattern p;
    p.n = 8;
    p.pinholes = {{0, 0}, {4, 4}};
    PatternState s(p);
    CHECK_FALSE(s.is_legal_move(1, {7, 7}));  // diagonal neighbour of (0,0) across the corner
    CHECK_FALSE(s.is_legal_move(1, {0, 7}));
    CHECK(s.is_legal_move(1, {0, 6}));        // distance 2 across the seam: legal
    CHECK(s.is_legal_move(0, {0, 1}));        // a pinhole's own exclusion does not block it
    CHECK_FALSE(s.is_legal_move(0, {4, 4}));  // occupied
}

namespace {

// Independent legality check for adding at `c`: brute-force torus distances to every pinhole.
bool brute_force_can_add(const Pattern& p, Cell c) {
    for (const Cell& q : p.pinholes) {
        if (q == c) return false;
        if (torus_distance_cells(q, c, p.n) < p.min_spacing_cells - kSpacingTolerance) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("add and remove moves equal full recomputation and keep the spacing rule") {
    struct Geometry {
        int n, holes, step;
        double spacing;
    };
    for (const Geometry g : {Geometry{16, 20, 2, 2.0}, Geometry{17, 12, 3, 2.5},
                             Geometry{5, 3, 2, 1.0}, Geometry{32, 40, 4, 3.0}}) {
        PatternState state(lattice_pattern(g.n, g.holes, g.step, g.spacing));
        std::mt19937_64 rng(static_cast<unsigned>(g.n * 100 + g.holes));
        std::uniform_int_distribution<int> pick_cell(0, g.n - 1), pick_kind(0, 2);
        int adds = 0, removes = 0, moves = 0;
        for (int m = 0; m < 6000; ++m) {
            const Cell c{pick_cell(rng), pick_cell(rng)};
            const int kind = pick_kind(rng);
            if (kind == 0) {
                const bool legal = state.can_add(c);
                REQUIRE(legal == brute_force_can_add(state.pattern(), c));
                if (legal) {
                    state.add(c);
                    ++adds;
                }
            } else if (kind == 1 && state.holes() > 1) {
                std::uniform_int_distribution<int> pick_hole(0, state.holes() - 1);
                state.remove(pick_hole(rng));
                ++removes;
            } else {
                std::uniform_int_distribution<int> pick_hole(0, state.holes() - 1);
                const int j = pick_hole(rng);
                const bool legal = state.is_legal_move(j, c);
                REQUIRE(legal == brute_force_legal(state.pattern(), j, c));
                if (legal) {
                    state.move(j, c);
                    ++moves;
                }
            }
        }
        INFO("n " << g.n << ": adds " << adds << ", removes " << removes << ", moves " << moves);
        CHECK(adds > 100);
        CHECK(removes > 100);
        CHECK(spacing_violations(state.pattern()).empty());
        const ComplexPlane full = pattern_spectrum(state.pattern());
        CHECK((state.spectrum() - full).abs().maxCoeff() <= kIncrementalSpectrumTol);
        CHECK(std::abs(state.spectrum()(0, 0).real() - state.holes()) <= kIncrementalSpectrumTol);
        CHECK(state.autocorrelation() == direct_autocorrelation(state.pattern()));
    }
}

TEST_CASE("adding across the seam respects the torus spacing rule") {
    Pattern p;
    p.n = 8;
    p.pinholes = {{0, 0}};
    PatternState s(p);
    CHECK_FALSE(s.can_add({7, 7}));  // diagonal neighbour across the corner
    CHECK_FALSE(s.can_add({0, 7}));
    CHECK_FALSE(s.can_add({0, 0}));  // occupied
    CHECK(s.can_add({0, 6}));        // distance 2 across the seam
    s.add({0, 6});
    CHECK_FALSE(s.can_add({0, 7}));
    s.remove(0);  // (0, 6) remains, now pinhole 0
    CHECK(s.pattern().pinholes.size() == 1);
    CHECK(s.pattern().pinholes[0] == Cell{0, 6});
    CHECK(s.can_add({0, 0}));        // distance 2 from (0, 6) across the seam: legal again
    CHECK_FALSE(s.can_add({1, 7}));  // diagonal neighbour of (0, 6)
}
