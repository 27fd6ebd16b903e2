#include <doctest/doctest.h>

#include <cmath>

#include "core/errors/error.hpp"
#include "design/pattern/pattern.hpp"

using namespace pinmask;

TEST_CASE("torus distance wraps across the seams") {
    CHECK(torus_distance_cells({0, 0}, {0, 15}, 16) == 1.0);
    CHECK(torus_distance_cells({0, 0}, {15, 15}, 16) == doctest::Approx(std::sqrt(2.0)));
    CHECK(torus_distance_cells({0, 0}, {8, 8}, 16) == doctest::Approx(std::sqrt(128.0)));
    CHECK(torus_distance_cells({3, 4}, {3, 4}, 16) == 0.0);
}

TEST_CASE("spacing rule: neighbours across the seam are violations, distance 2 is legal") {
    Pattern p;
    p.n = 16;
    p.pinholes = {{0, 0}, {0, 2}, {2, 0}};
    CHECK(spacing_violations(p).empty());
    p.pinholes.push_back({15, 15});  // diagonal neighbour of (0,0) through the corner seam
    const auto v = spacing_violations(p);
    REQUIRE(v.size() == 1);
    CHECK(v[0].distance_cells == doctest::Approx(std::sqrt(2.0)));
    CHECK_THROWS_AS(validate(p), InvalidInput);
    CHECK_NOTHROW(validate(p, /*allow_spacing_violations=*/true));
}

TEST_CASE("each violating pair is reported once, also on tiny even tori") {
    Pattern p;
    p.n = 2;
    p.min_spacing_cells = 1.0;
    p.pinholes = {{0, 0}, {0, 1}};
    // n = 2 >= spacing 1: no self-violation; the pair is at distance 1: legal.
    CHECK(spacing_violations(p).empty());
    p.min_spacing_cells = 1.5;
    const auto v = spacing_violations(p);
    // Both pinholes are closer than 1.5 to their own copies (n = 2 < 1.5? no) -> only the pair.
    REQUIRE(v.size() == 1);
    CHECK(v[0].a == Cell{0, 0});
    CHECK(v[0].b == Cell{0, 1});
}

TEST_CASE("a pinhole on a torus smaller than the spacing violates against its own copy") {
    Pattern p;
    p.n = 1;
    p.pinholes = {{0, 0}};
    const auto v = spacing_violations(p);
    REQUIRE(v.size() == 1);
    CHECK(v[0].a == v[0].b);
}

TEST_CASE("structural validation names the problem") {
    Pattern p;
    p.n = 16;
    p.pinholes = {{0, 0}, {16, 3}};
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("outside the 16 x 16 grid"), InvalidInput);
    p.pinholes = {{0, 0}, {0, 0}};
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("duplicate"), InvalidInput);
    p.pinholes = {};
    p.n = 0;
    CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("pattern.n"), InvalidInput);
    p.n = 4097;
    CHECK_THROWS_AS(validate(p), InvalidInput);
}
