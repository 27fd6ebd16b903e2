#include <doctest/doctest.h>

#include <vector>

#include "core/errors/error.hpp"
#include "export/layout/dark_tone.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/shapes.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;
using pinmask::test::cover_count;
using pinmask::test::inside;
using pinmask::test::is_simple;

namespace {

// Pieces must tile outline minus holes: every sample point of the outline lies in exactly one
// piece unless it lies in a hole (then in none). Samples sit at half-nanometre offsets, never
// on an edge. Also: exact area identity, simplicity, counter-clockwise, vertex cap.
void check_pieces(const std::vector<Ring>& pieces, const BoxNm& outline,
                  const std::vector<Ring>& holes, std::size_t cap, int samples_per_side) {
    __int128 area = 0;
    for (const Ring& r : pieces) {
        CHECK(r.size() <= cap);
        CHECK(doubled_area(r) > 0);
        CHECK(is_simple(r));
        area += doubled_area(r);
    }
    __int128 expected = __int128(2) * (outline.x1 - outline.x0) * (outline.y1 - outline.y0);
    for (const Ring& h : holes) expected -= doubled_area(h);
    CHECK(area == expected);
    const double sx = double(outline.x1 - outline.x0) / samples_per_side;
    const double sy = double(outline.y1 - outline.y0) / samples_per_side;
    for (int i = 0; i < samples_per_side; ++i)
        for (int j = 0; j < samples_per_side; ++j) {
            const double x = std::floor(outline.x0 + (i + 0.37) * sx) + 0.5;
            const double y = std::floor(outline.y0 + (j + 0.61) * sy) + 0.5;
            const int in_hole = cover_count(holes, x, y);
            INFO("sample " << x << ", " << y);
            CHECK(cover_count(pieces, x, y) == 1 - in_hole);
        }
}

}  // namespace

TEST_CASE("box minus a convex polygon: hole-free pieces for 3..40 sides and small caps") {
    const BoxNm box{-1000, -1000, 1000, 1000};
    for (int sides = 3; sides <= 40; sides += (sides < 10 ? 1 : 7))
        for (std::size_t cap : {std::size_t(8), std::size_t(11), std::size_t(199)}) {
            const Ring hole = regular_polygon(13.0, -7.0, 900.0, sides, box, 1);
            const std::vector<Ring> pieces = box_minus_convex(box, hole, cap);
            INFO("sides " << sides << " cap " << cap);
            check_pieces(pieces, box, {hole}, cap, 40);
        }
    // Polygons with vertical end edges (a square, an octagon with flat sides) get side boxes.
    const Ring square = box_ring({-500, -400, 300, 600});
    check_pieces(box_minus_convex(box, square, 8), box, {square}, 8, 40);
    CHECK_THROWS_AS(box_minus_convex(box, box_ring(box), 8), InvalidInput);
}

TEST_CASE("dark tone with squares: rectangles that tile the outline minus the pinholes") {
    LayoutOptions o;
    o.tone = Tone::kDark;
    o.frame_m = 100e-6;
    const Mask m = pinmask::test::golden_mask();
    const Layout dark = make_layout(m, o);
    const Layout clear = make_layout(m, LayoutOptions{.frame_m = 100e-6});
    const BoxNm& a = dark.active_area;
    const BoxNm outline{a.x0 - 100000, a.y0 - 100000, a.x1 + 100000, a.y1 + 100000};
    for (const Ring& r : dark.polygons) CHECK(r.size() == 4);
    check_pieces(dark.polygons, outline, clear.polygons, 4, 60);
    CHECK(dark.extent.x0 == outline.x0);
}

TEST_CASE("dark tone with touching squares (dense pattern, tiled) and with smaller squares") {
    for (int n : {5, 8, 11}) {
        const Mask m = pinmask::test::random_dense_mask(n, 0.5, 7u + n, 2);
        LayoutOptions o;
        o.tone = Tone::kDark;
        const Layout dark = make_layout(m, o);
        const Layout clear = make_layout(m, {});
        check_pieces(dark.polygons, dark.active_area, clear.polygons, 4, 4 * n);
    }
    const Mask m = pinmask::test::golden_mask();
    LayoutOptions o;
    o.tone = Tone::kDark;
    o.hole_side_m = 300e-6;
    LayoutOptions c;
    c.hole_side_m = 300e-6;
    check_pieces(make_layout(m, o).polygons, make_layout(m, c).active_area,
                 make_layout(m, c).polygons, 4, 50);
}

TEST_CASE("dark tone with circles: pieces around every hole, capped, no hole enclosed") {
    const Mask m = pinmask::test::mask_with(5, {{0, 0}, {0, 1}, {2, 2}, {4, 3}}, 1, 1, 440e-6);
    for (std::size_t cap : {std::size_t(12), std::size_t(199)}) {
        LayoutOptions o;
        o.shape = HoleShape::kCircle;
        o.chord_tolerance_m = 50e-9;
        o.tone = Tone::kDark;
        o.max_vertices = cap;
        o.frame_m = 50e-6;
        const Layout dark = make_layout(m, o);
        o.tone = Tone::kClear;
        o.max_vertices = 1000;  // the same circles, each one polygon, as the reference holes
        const Layout clear = make_layout(m, o);
        const BoxNm& a = dark.active_area;
        INFO("cap " << cap);
        check_pieces(dark.polygons, {a.x0 - 50000, a.y0 - 50000, a.x1 + 50000, a.y1 + 50000},
                     clear.polygons, cap, 50);
        // Each circle's centre is in no piece; a point just inside its cell corner is in one.
        for (const Ring& h : clear.polygons) {
            const BoxNm b = bounding_box({h});
            CHECK(cover_count(dark.polygons, (b.x0 + b.x1) / 2 + 0.5, (b.y0 + b.y1) / 2 + 0.5) ==
                  0);
            CHECK(inside(h, (b.x0 + b.x1) / 2 + 0.5, (b.y0 + b.y1) / 2 + 0.5));
        }
    }
}

TEST_CASE("dark_pieces checks its cap") {
    CHECK_THROWS_AS(dark_pieces({0, 0, 10, 10}, {}, {}, 4), InvalidInput);
    const std::vector<Ring> whole = dark_pieces({0, 0, 10, 10}, {}, {}, 8);
    CHECK(canonical_rings(whole) == canonical_rings({box_ring({0, 0, 10, 10})}));
}
