// The fabrication grid (design/optics/fab_grid): the pitch rounded to whole grid steps, and the
// spacing rule on that pitch against a brute-force reference over every pair of pinholes (torus
// distances written out here).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/errors/error.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/pattern/pattern.hpp"

using namespace pinmask;

namespace {

struct Reference {
    std::size_t violations = 0;
    double closest_nm = std::numeric_limits<double>::infinity();
};

// Every pair, the shortest torus offset per axis, distance sqrt(dr^2 + dc^2) P.
Reference brute_force(const Pattern& p, double pitch_nm) {
    Reference r;
    const double limit = p.min_spacing_cells * pitch_nm - 1e-3;
    for (std::size_t a = 0; a < p.pinholes.size(); ++a)
        for (std::size_t b = a + 1; b < p.pinholes.size(); ++b) {
            int dr = std::abs(p.pinholes[a].row - p.pinholes[b].row);
            int dc = std::abs(p.pinholes[a].col - p.pinholes[b].col);
            dr = std::min(dr, p.n - dr);
            dc = std::min(dc, p.n - dc);
            const double d = std::sqrt(double(dr * dr + dc * dc)) * pitch_nm;
            r.closest_nm = std::min(r.closest_nm, d);
            if (d < limit) ++r.violations;
        }
    return r;
}

}  // namespace

TEST_CASE("the pitch on the grid is d rounded to whole grid steps") {
    CHECK(pitch_on_grid_nm(455.40571e-6, 1) == 455406);
    CHECK(pitch_on_grid_nm(455.40571e-6, 1000) == 455000);
    CHECK(pitch_on_grid_nm(455.6e-6, 1000) == 456000);
    CHECK(pitch_on_grid_nm(440e-6, 7) == 439999);  // 62857.14 steps of 7 nm -> 62857
    CHECK(pitch_on_grid_nm(3e-9, 10) == 10);       // at least one step
    CHECK(pinhole_on_grid_m(339.609e-6, 1000) == doctest::Approx(340e-6).epsilon(1e-15));
    CHECK_THROWS_AS(pitch_on_grid_nm(-1e-6, 1), InvalidInput);
    CHECK_THROWS_AS(pitch_on_grid_nm(2.0, 1), InvalidInput);
    CHECK(fab_grid_nm(1e-6, "grid") == 1000);
    CHECK_THROWS_AS(fab_grid_nm(1.5e-9, "grid"), InvalidInput);
    CHECK_THROWS_AS(fab_grid_nm(0.0, "grid"), InvalidInput);
}

TEST_CASE("spacing on the grid equals a brute-force count over every pair") {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 40; ++trial) {
        Pattern p;
        p.n = 5 + int(rng() % 20);
        p.min_spacing_cells = 1.0 + double(rng() % 300) / 100.0;
        const int holes = 1 + int(rng() % (p.n * p.n / 3));
        std::vector<bool> used(std::size_t(p.n * p.n));
        while (int(p.pinholes.size()) < holes) {
            const int r = int(rng() % p.n), c = int(rng() % p.n);
            if (used[std::size_t(r * p.n + c)]) continue;
            used[std::size_t(r * p.n + c)] = true;
            p.pinholes.push_back({r, c});
        }
        const double d_m = (300 + double(rng() % 200000) * 1e-3) * 1e-6;
        const std::int64_t grid = trial % 2 ? 1 : 1000;
        const GridSpacing g = spacing_on_grid(p, d_m, grid);
        const double pitch = double(std::llround(d_m * 1e9 / double(grid)) * grid);
        CHECK(double(g.pitch_nm) == pitch);
        const Reference ref = brute_force(p, pitch);
        INFO("trial " << trial << " n " << p.n << " spacing " << p.min_spacing_cells);
        CHECK(g.violations == ref.violations);
        // The closest pair is found whenever it lies within the rule's reach.
        if (ref.closest_nm <= std::ceil(p.min_spacing_cells) * pitch && p.pinholes.size() > 1)
            CHECK(g.closest_nm == doctest::Approx(ref.closest_nm).epsilon(1e-15));
    }
}

TEST_CASE("a rule one grid step above a pair's distance is a violation, at the step it is not") {
    Pattern p;
    p.n = 8;
    p.pinholes = {{0, 0}, {0, 2}};
    const std::int64_t pitch = 455406;
    p.min_spacing_cells = double(2 * pitch + 1) / double(pitch);
    GridSpacing g = spacing_on_grid(p, 455.40571e-6, 1);
    CHECK(g.violations == 1);
    CHECK(g.closest_nm == doctest::Approx(2.0 * pitch));
    CHECK(g.limit_nm == doctest::Approx(2.0 * pitch + 1));
    p.min_spacing_cells = 2.0;
    g = spacing_on_grid(p, 455.40571e-6, 1);
    CHECK(g.violations == 0);
    CHECK(spacing_rule_text(2.0, pitch, 1) ==
          "pinhole centres >= 910.812 um (2 x pitch 455.406 um on the 1 nm grid)");
}
