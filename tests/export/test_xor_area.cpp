// XOR area of polygon sets against hand-computed areas and an independent raster count.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/errors/error.hpp"
#include "export/layout/xor_area.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

// The areas below are integers far below 2^53 nm^2, computed exactly and converted once: the
// comparison is exact, not approximate.
constexpr double kExactArea = 0.0;

Ring rect(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

}  // namespace

TEST_CASE("identical sets have zero XOR area") {
    const std::vector<Ring> a = {rect(0, 0, 1000, 1000), rect(3000, -500, 3700, 2100)};
    CHECK(xor_area_nm2(a, a) == kExactArea);
    CHECK(xor_area_nm2({}, {}) == kExactArea);
    // Touching pieces (one group) in another order, starting at other vertices: still equal.
    const std::vector<Ring> pieces = {rect(0, 0, 1000, 1000), rect(1000, 0, 2000, 500),
                                      rect(1000, 500, 2000, 1000)};
    std::vector<Ring> shuffled = {pieces[2], pieces[0], pieces[1]};
    std::rotate(shuffled[1].begin(), shuffled[1].begin() + 2, shuffled[1].end());
    CHECK(xor_area_nm2(pieces, shuffled) == kExactArea);
    // The same group with one piece changed goes through the exact Boolean operation.
    shuffled[0] = rect(1000, 500, 2000, 1200);
    CHECK(xor_area_nm2(pieces, shuffled) == 200'000.0);
}

TEST_CASE("XOR of a square and its shifted copy is the hand-computed value") {
    const Ring s = rect(0, 0, 1000, 1000);
    // Shift (300, 0): two 300 x 1000 slivers.
    CHECK(xor_area_nm2({s}, {rect(300, 0, 1300, 1000)}) == 600'000.0);
    // Shift (300, 400): overlap 700 x 600, xor = 2 (10^6 - 420000).
    CHECK(xor_area_nm2({s}, {rect(300, 400, 1300, 1400)}) == 1'160'000.0);
    // Disjoint: both areas.
    CHECK(xor_area_nm2({s}, {rect(5000, 0, 6000, 1000)}) == 2'000'000.0);
    // Against nothing: its own area.
    CHECK(xor_area_nm2({s}, {}) == 1'000'000.0);
}

TEST_CASE("a set and its union-merged form cover the same region") {
    // Overlapping and edge-touching pieces against the single merged rectangle.
    const std::vector<Ring> pieces = {rect(0, 0, 1000, 1000), rect(500, 0, 1500, 1000),
                                      rect(1500, 0, 2000, 1000)};
    CHECK(xor_area_nm2(pieces, {rect(0, 0, 2000, 1000)}) == kExactArea);
    CHECK(union_area_nm2(pieces) == 2'000'000.0);
    CHECK(intersection_area_nm2({pieces[0]}, {pieces[1]}) == 500'000.0);
    // Touching boundaries intersect in a set of measure zero.
    CHECK(intersection_area_nm2({pieces[1]}, {pieces[2]}) == kExactArea);
}

TEST_CASE("orientation does not matter, non-rectilinear shapes are exact") {
    const Ring ccw = rect(-1000, -1000, 1000, 1000);
    const Ring cw(ccw.rbegin(), ccw.rend());
    CHECK(xor_area_nm2({ccw}, {cw}) == kExactArea);
    // A diamond inscribed in the square: half of the square's 4e6 nm^2.
    const Ring diamond = {{1000, 0}, {0, 1000}, {-1000, 0}, {0, -1000}};
    CHECK(xor_area_nm2({ccw}, {diamond}) == 2'000'000.0);
    // Diamond against [-300, 1000] x [-1000, 1000]: the diamond loses the triangle x < -300
    // (apex (-1000, 0), base 1400 at x = -300, height 700: area 700^2).
    const double cut = 700.0 * 700.0;
    CHECK(intersection_area_nm2({diamond}, {rect(-300, -1000, 1000, 1000)}) == 2'000'000.0 - cut);
    CHECK(xor_area_nm2({diamond}, {rect(-300, -1000, 1000, 1000)}) ==
          2'000'000.0 + 2'600'000.0 - 2.0 * (2'000'000.0 - cut));
}

TEST_CASE("intersections at rational points stay exact until the final rounding") {
    // T1 = (0,0),(1000,0),(0,1000); T2 = (0,0),(1000,0),(1000,300). The hypotenuse x + y = 1000
    // meets y = 0.3 x at (10000/13, 3000/13): T1 n T2 has area 1000 * (3000/13) / 2, and
    // XOR = 500000 + 150000 - 2 * 1500000/13 = 5450000/13 nm^2.
    const Ring t1 = {{0, 0}, {1000, 0}, {0, 1000}};
    const Ring t2 = {{0, 0}, {1000, 0}, {1000, 300}};
    // The exact rational is converted to double once (GMP truncates): within 2 ulp.
    constexpr double kOneRounding = 4.5e-16;
    CHECK_CLOSE(xor_area_nm2({t1}, {t2}), 5'450'000.0 / 13.0, kOneRounding);
    CHECK_CLOSE(intersection_area_nm2({t1}, {t2}), 1'500'000.0 / 13.0, kOneRounding);
}

TEST_CASE("XOR of random unit-cell sets matches a raster count") {
    // Squares on a grid of 1000 nm cells: the XOR area is (cells covered by exactly one set)
    // * 10^6 nm^2, counted directly on the raster.
    std::mt19937_64 rng(42);
    for (const int grid : {13, 16, 17}) {
        CAPTURE(grid);
        std::uniform_int_distribution<int> pos(0, grid - 1), len(1, 4);
        std::vector<int> occ_a(grid * grid, 0), occ_b(grid * grid, 0);
        std::vector<Ring> a, b;
        for (int set = 0; set < 2; ++set) {
            for (int k = 0; k < 12; ++k) {
                const int x0 = pos(rng), y0 = pos(rng);
                const int x1 = std::min(grid, x0 + len(rng)), y1 = std::min(grid, y0 + len(rng));
                (set ? b : a).push_back(rect(x0 * 1000, y0 * 1000, x1 * 1000, y1 * 1000));
                for (int y = y0; y < y1; ++y) {
                    for (int x = x0; x < x1; ++x) (set ? occ_b : occ_a)[y * grid + x] = 1;
                }
            }
        }
        double cells = 0;
        for (int i = 0; i < grid * grid; ++i) cells += (occ_a[i] != occ_b[i]);
        CHECK(xor_area_nm2(a, b) == cells * 1e6);
    }
}

TEST_CASE("bad rings are invalid input naming the set and ring") {
    const Ring bowtie = {{0, 0}, {1000, 1000}, {1000, 0}, {0, 1000}};
    CHECK_THROWS_WITH_AS(xor_area_nm2({rect(0, 0, 1, 1)}, {bowtie}), doctest::Contains("b[0]"),
                         InvalidInput);
    CHECK_THROWS_AS(xor_area_nm2({{{0, 0}, {1, 1}}}, {}), InvalidInput);
    CHECK_THROWS_AS(xor_area_nm2({rect(0, 0, kMaxCoordNm + 1, 10)}, {}), InvalidInput);
}

TEST_CASE("the holes of a union of opaque pieces are the clear regions, exactly") {
    // Five pieces sharing edges leave two square holes.
    const std::vector<Ring> pieces = {rect(0, 0, 4000, 1000), rect(0, 2000, 4000, 4000),
                                      rect(0, 1000, 1000, 2000), rect(2000, 1000, 2500, 2000),
                                      rect(3500, 1000, 4000, 2000)};
    const auto holes = union_holes(pieces);
    REQUIRE(holes.size() == 2);
    CHECK(xor_area_nm2(holes, {rect(1000, 1000, 2000, 2000), rect(2500, 1000, 3500, 2000)}) ==
          kExactArea);
    // A piece further away adds no hole; a notch open to the outside is not a hole.
    auto more = pieces;
    more.push_back(rect(6000, 0, 7000, 1000));
    more.erase(more.begin() + 4);  // hole 1 now opens to the right edge
    CHECK(union_holes(more).size() == 1);
    // A hole whose vertices fall between grid points (crossing diagonals) is refused.
    const std::vector<Ring> skew = {{{0, 0}, {3, 0}, {3, 1}},
                                    {{3, 0}, {3, 3}, {2, 3}},
                                    {{3, 3}, {0, 3}, {0, 2}},
                                    {{0, 3}, {0, 0}, {1, 0}}};
    CHECK_THROWS_AS(union_holes(skew), InvalidInput);
}
