#include <doctest/doctest.h>

#include <vector>

#include "core/errors/error.hpp"
#include "export/layout/cell_union.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;
using pinmask::test::cover_count;
using pinmask::test::is_simple;
using pinmask::test::mask_with;

namespace {

// The union must equal the occupancy exactly: sample every cell at its centre and near each
// corner (offset by a quarter pitch, plus half a nanometre so no sample lies on an edge).
void check_union_matches_occupancy(const Mask& m, const Layout& l, std::size_t max_vertices) {
    const Pattern& p = m.pattern;
    const std::int64_t d = std::llround(m.camera.pinhole_m * 1e9);
    const int rows = p.n * p.tiles_rows, cols = p.n * p.tiles_cols;
    const std::vector<std::uint8_t> occ = occupancy(p);
    std::int64_t cells = 0;
    for (const Ring& r : l.polygons) {
        CHECK(r.size() <= max_vertices);
        CHECK(doubled_area(r) > 0);
        CHECK(is_simple(r));
    }
    __int128 area = 0;
    for (const Ring& r : l.polygons) area += doubled_area(r);
    for (int R = 0; R < rows; ++R)
        for (int C = 0; C < cols; ++C) {
            const int want = occ[std::size_t(R % p.n) * p.n + C % p.n];
            cells += want;
            const double x0 = double(C) * d - double(cols) * d / 2;
            const double y1 = double(rows) * d / 2 - double(R) * d;
            for (double fx : {0.25, 0.5, 0.75})
                for (double fy : {0.25, 0.5, 0.75}) {
                    const double x = x0 + fx * d + 0.5, y = y1 - fy * d + 0.5;
                    INFO("cell " << R << "," << C << " sample " << fx << "," << fy);
                    CHECK(cover_count(l.polygons, x, y) == want);
                }
        }
    CHECK(area == __int128(cells) * 2 * d * d);
}

}  // namespace

TEST_CASE("a ring of 8 touching cells becomes two hole-free pieces, cut at the hole's top") {
    // 3 x 3 block without its centre: the union has a hole, which no GDSII boundary may have.
    const Mask m = mask_with(3, {{0, 0}, {0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}, {2, 2}});
    const Layout l = make_layout(m, {});
    const std::int64_t d = 100000;
    const Ring top = box_ring({-3 * d / 2, d / 2, 3 * d / 2, 3 * d / 2});
    const Ring u = {{-3 * d / 2, -3 * d / 2}, {3 * d / 2, -3 * d / 2}, {3 * d / 2, d / 2},
                    {d / 2, d / 2},           {d / 2, -d / 2},         {-d / 2, -d / 2},
                    {-d / 2, d / 2},          {-3 * d / 2, d / 2}};
    CHECK(canonical_rings(l.polygons) == canonical_rings({top, u}));
    check_union_matches_occupancy(m, l, 199);
}

TEST_CASE("pinholes touching across a tile seam are merged") {
    // Row 0 of a 1 x 2 tiling of n = 4: cells 0, 3 | 4, 7; 3 and 4 meet at the seam.
    const Mask m = mask_with(4, {{0, 0}, {0, 3}}, 1, 2);
    const Layout l = make_layout(m, {});
    const std::int64_t d = 100000;
    CHECK(canonical_rings(l.polygons) ==
          canonical_rings({box_ring({-4 * d, d, -3 * d, 2 * d}), box_ring({-d, d, d, 2 * d}),
                           box_ring({3 * d, d, 4 * d, 2 * d})}));
    // Without tiling nothing touches: three separate squares... two, the pattern has two.
    CHECK(make_layout(mask_with(4, {{0, 0}, {0, 3}}), {}).polygons.size() == 2);
}

TEST_CASE("corner contacts stay separate polygons (their union is not a simple polygon)") {
    const Mask m = mask_with(4, {{0, 1}, {1, 0}, {1, 2}, {2, 1}});
    const Layout l = make_layout(m, {});
    CHECK(l.polygons.size() == 4);
    check_union_matches_occupancy(m, l, 199);
}

TEST_CASE("dense MURA-like patterns: exact union, simple hole-free pieces, vertex cap") {
    for (int n : {7, 13, 16, 31})
        for (std::uint64_t seed : {1u, 2u})
            for (int tiles : {1, 2})
                for (std::size_t cap : {std::size_t(8), std::size_t(199)}) {
                    const Mask m = pinmask::test::random_dense_mask(n, 0.5, seed * 100 + n, tiles);
                    LayoutOptions o;
                    o.max_vertices = cap;
                    const Layout l = make_layout(m, o);
                    INFO("n " << n << " seed " << seed << " tiles " << tiles << " cap " << cap);
                    check_union_matches_occupancy(m, l, cap);
                    // Merging happened: fewer pieces than pinholes.
                    CHECK(l.polygons.size() <
                          m.pattern.pinholes.size() * std::size_t(tiles * tiles));
                }
}

TEST_CASE("union_of_cells checks its arguments") {
    const std::vector<std::uint8_t> occ{1, 1};
    const std::vector<std::int64_t> xe{0, 1, 2}, ye{1, 0};
    CHECK_THROWS_AS(union_of_cells(occ, 1, 2, xe, ye, 3), InvalidInput);
    CHECK_THROWS_AS(union_of_cells(occ, 1, 3, xe, ye, 8), InvalidInput);
    CHECK(union_of_cells(occ, 1, 2, xe, ye, 8).size() == 1);
}
