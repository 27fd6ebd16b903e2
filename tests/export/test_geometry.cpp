#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors/error.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/marks.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/shapes.hpp"
#include "export/pipeline/drc.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;
using pinmask::test::golden_mask;
using pinmask::test::mask_with;

namespace {

// Snapping moves each coordinate by less than one grid step, so a vertex moves by < sqrt(2) g.
constexpr double kSnapShiftGrids = std::numbers::sqrt2;

Ring box(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
    return box_ring({x0, y0, x1, y1});
}

}  // namespace

TEST_CASE("row 0 is the top row, column 0 the left column, origin at the mask centre") {
    const Layout l = make_layout(golden_mask(), {});
    // 4 x 4 cells of 440 um: x and y run from -880 um to +880 um.
    CHECK(l.active_area.x0 == -880000);
    CHECK(l.active_area.y1 == 880000);
    CHECK(l.extent.x1 == 880000);
    const std::vector<Ring> expected = canonical_rings({
        box(-880000, 440000, -440000, 880000),  // (0, 0): top-left cell
        box(0, 0, 440000, 440000),              // (1, 2)
        box(0, -880000, 440000, -440000),       // (3, 2): bottom row
    });
    CHECK(canonical_rings(l.polygons) == expected);
    CHECK(l.annotations.empty());
    CHECK(l.mask_hash == geometry_hash(golden_mask()));
    for (const Ring& r : l.polygons) CHECK(doubled_area(r) == 2LL * 440000 * 440000);
}

TEST_CASE("tiling repeats the pattern at whole-pattern offsets (odd n, unequal tiles)") {
    const int n = 5, tr = 3, tc = 2;
    const std::int64_t d = 100000;
    const Mask m = mask_with(n, {{0, 1}, {2, 4}, {4, 2}}, tr, tc, 100e-6);
    const Layout l = make_layout(m, {});
    std::vector<Ring> expected;
    const std::int64_t half_w = n * tc * d / 2, half_h = n * tr * d / 2;
    for (int a = 0; a < tr; ++a)
        for (int b = 0; b < tc; ++b)
            for (const Cell& c : m.pattern.pinholes) {
                const std::int64_t row = a * n + c.row, col = b * n + c.col;
                expected.push_back(box(col * d - half_w, half_h - (row + 1) * d,
                                       (col + 1) * d - half_w, half_h - row * d));
            }
    CHECK(l.polygons.size() == expected.size());
    CHECK(canonical_rings(l.polygons) == canonical_rings(expected));
}

TEST_CASE("cell edges are snapped to the grid and shared by neighbours") {
    Mask m = mask_with(7, {{0, 0}, {0, 1}, {3, 3}, {6, 6}});
    m.camera.pinhole_m = 333.3333e-6;  // not a whole number of grid steps
    LayoutOptions o;
    o.grid_m = 5e-9;
    o.tone = Tone::kDark;
    const Layout l = make_layout(m, o);
    for (const Ring& r : l.polygons)
        for (const PointNm& p : r) {
            CHECK(p.x % 5 == 0);
            CHECK(p.y % 5 == 0);
        }
    const Layout c = make_layout(m, LayoutOptions{.grid_m = 5e-9});
    for (const Ring& r : c.polygons) {
        const BoxNm b = bounding_box({r});
        // (0,0) and (0,1) merge into one 2-cell piece; the rest are single cells.
        const double w = double(b.x1 - b.x0), h = double(b.y1 - b.y0);
        CHECK(std::fabs(h - 333333.3) <= 5.0);
        CHECK((std::fabs(w - 333333.3) <= 5.0 || std::fabs(w - 666666.6) <= 5.0));
    }
    CHECK(c.polygons.size() == 3);
}

TEST_CASE("chord tolerance: the fewest sides (multiple of 4) whose sagitta is within it") {
    for (double r : {50.0, 1000.0, 220000.0, 1.5e6})
        for (double tol : {0.5, 3.0, 10.0, 100.0}) {
            const int n = sides_for_chord_tolerance(r, tol);
            INFO("r = " << r << " nm, tol = " << tol << " nm, N = " << n);
            CHECK(n % 4 == 0);
            CHECK(n >= 8);
            // Independent sagitta: radius minus the distance from the centre to the midpoint
            // of the chord between two adjacent vertices at angles pi/N and 3 pi/N.
            auto sag = [r](int k) {
                const double a = std::numbers::pi / k, b = 3 * std::numbers::pi / k;
                const double mx = r * (std::cos(a) + std::cos(b)) / 2;
                const double my = r * (std::sin(a) + std::sin(b)) / 2;
                return r - std::hypot(mx, my);
            };
            constexpr double kRoundOff = 1e-9;  // relative, of r - |midpoint| in double
            CHECK(sag(n) <= tol + kRoundOff * r);
            if (n > 8) CHECK(sag(n - 4) > tol - kRoundOff * r);
        }
    CHECK_THROWS_AS(sides_for_chord_tolerance(220000.0, 1e-6), InvalidInput);
    CHECK_THROWS_AS(sides_for_chord_tolerance(220000.0, 0.0), InvalidInput);
}

TEST_CASE("circle sides: within max_vertices, auto the finest that fits, too fine refused") {
    // auto: the largest multiple of 4 within the limit, but no finer than one grid step.
    CHECK(circle_sides(220000.0, 0.0, 199, 1) == 196);
    CHECK(circle_sides(220000.0, 0.0, 8, 1) == 8);
    CHECK(circle_sides(1000.0, 0.0, 199, 1) == sides_for_chord_tolerance(1000.0, 1.0));
    CHECK(sagitta_nm(1000.0, circle_sides(1000.0, 0.0, 199, 1)) <= 1.0);
    // An explicit tolerance: the fewest sides within it, when they fit.
    CHECK(circle_sides(220000.0, 200.0, 199, 1) == sides_for_chord_tolerance(220000.0, 200.0));
    CHECK_THROWS_WITH_AS(circle_sides(220000.0, 10.0, 199, 1),
                         doctest::Contains("needs 332 vertices"), InvalidInput);
    CHECK_THROWS_WITH_AS(circle_sides(220000.0, 10.0, 199, 1),
                         doctest::Contains("finest tolerance within them is 29 nm"), InvalidInput);
    CHECK(sagitta_nm(220000.0, 196) <= 29.0);
    CHECK_THROWS_AS(circle_sides(220000.0, 0.0, 7, 1), InvalidInput);

    // Regression: the default circle export (then a 10 nm tolerance, 332 vertices) failed its
    // own design-rule check (vertex limit 199). Now every circle fits and the DRC is clean.
    const Mask m = mask_with(6, {{0, 0}, {2, 3}, {5, 5}}, 1, 1, 440e-6);
    LayoutOptions o;
    o.shape = HoleShape::kCircle;
    const Layout l = make_layout(m, o);
    CHECK(l.hole_sides == 196);
    for (const Ring& p : l.polygons) CHECK(p.size() <= o.max_vertices);
    DrcRules rules;
    rules.max_vertices = o.max_vertices;  // as pinmask export checks its own output
    CHECK(run_drc(l, rules).clean());
    o.chord_tolerance_m = 10e-9;
    CHECK_THROWS_AS(make_layout(m, o), InvalidInput);
    o.tone = Tone::kDark;  // holes in pieces split to max_vertices: a finer circle is allowed
    CHECK_NOTHROW(make_layout(m, o));
}

TEST_CASE("circles: inscribed, convex, strictly inside their cell, area of the N-gon") {
    const Mask m = mask_with(6, {{0, 0}, {0, 1}, {2, 3}, {5, 5}}, 1, 1, 440e-6);
    for (double tol_nm : {10.0, 200.0}) {
        LayoutOptions o;
        o.shape = HoleShape::kCircle;
        o.chord_tolerance_m = tol_nm * 1e-9;
        o.max_vertices = 1000;  // 10 nm on a 220 um radius needs 332 sides
        const Layout l = make_layout(m, o);
        const double r = 220000.0;
        const int n = sides_for_chord_tolerance(r, tol_nm);
        REQUIRE(l.polygons.size() == 4);
        for (std::size_t i = 0; i < l.polygons.size(); ++i) {
            const Ring& p = l.polygons[i];
            const Cell c = sorted_pinholes(m.pattern)[i];
            const double cx = (c.col + 0.5) * 440000.0 - 3 * 440000.0;
            const double cy = 3 * 440000.0 - (c.row + 0.5) * 440000.0;
            CHECK(p.size() == std::size_t(n));
            CHECK(is_strictly_convex_ccw(p));
            double perimeter = 0;
            for (std::size_t k = 0; k < p.size(); ++k) {
                const double dist = std::hypot(p[k].x - cx, p[k].y - cy);
                CHECK(dist <= r + 1e-6);
                CHECK(dist >= r - kSnapShiftGrids);
                const PointNm& q = p[(k + 1) % p.size()];
                perimeter += std::hypot(double(q.x - p[k].x), double(q.y - p[k].y));
            }
            // Area of the exact inscribed N-gon; snapping shifts the boundary by < sqrt(2) g.
            const double exact = 0.5 * n * r * r * std::sin(2 * std::numbers::pi / n);
            CHECK(std::fabs(double(doubled_area(p)) / 2 - exact) <= perimeter * kSnapShiftGrids);
        }
        // Neighbouring circles (cells (0,0) and (0,1)) do not touch: a gap of >= 2 grid steps.
        const BoxNm a = bounding_box({l.polygons[0]}), b = bounding_box({l.polygons[1]});
        CHECK(b.x0 - a.x1 >= 2);
    }
}

TEST_CASE("regular polygons with a given number of sides, and smaller squares") {
    const Mask m = mask_with(3, {{1, 1}}, 1, 1, 440e-6);
    for (int sides : {3, 5, 6, 7, 12}) {
        LayoutOptions o;
        o.shape = HoleShape::kPolygon;
        o.polygon_sides = sides;
        const Layout l = make_layout(m, o);
        REQUIRE(l.polygons.size() == 1);
        CHECK(l.polygons[0].size() == std::size_t(sides));
        CHECK(is_strictly_convex_ccw(l.polygons[0]));
    }
    LayoutOptions o;
    o.hole_side_m = 300e-6;
    const Layout l = make_layout(m, o);
    CHECK(canonical_rings(l.polygons) == canonical_rings({box(-150000, -150000, 150000, 150000)}));
}

TEST_CASE("mirroring maps x -> -x for polygons, marks and label") {
    LayoutOptions o;
    o.marks = true;
    o.label_lines = default_label_lines(golden_mask(), "golden");
    o.frame_m = 100e-6;
    const Layout plain = make_layout(golden_mask(), o);
    o.mirror = true;
    const Layout mirrored = make_layout(golden_mask(), o);
    CHECK(mirrored.mirrored);
    std::vector<Ring> expected;
    for (const Ring& r : all_rings(plain)) expected.push_back(mirrored_about_y_axis(r));
    CHECK(canonical_rings(all_rings(mirrored)) == canonical_rings(expected));
    CHECK(mirrored.extent.x0 == -plain.extent.x1);
    CHECK(mirrored.extent.x1 == -plain.extent.x0);
    for (const Ring& r : mirrored.polygons) CHECK(doubled_area(r) > 0);
    // The top-left pinhole moves to the top-right.
    CHECK(bounding_box({mirrored.polygons[0]}).x0 == 440000);
}

TEST_CASE("marks and label lie outside the outline and no two of their pieces touch") {
    LayoutOptions o;
    o.marks = true;
    o.frame_m = 200e-6;
    o.label_lines = default_label_lines(golden_mask(), "golden-1");
    const Layout l = make_layout(golden_mask(), o);
    const BoxNm outline{l.active_area.x0 - 200000, l.active_area.y0 - 200000,
                        l.active_area.x1 + 200000, l.active_area.y1 + 200000};
    REQUIRE(l.annotations.size() > 4);
    std::vector<BoxNm> boxes;
    for (const Ring& r : l.annotations) {
        const BoxNm b = bounding_box({r});
        const bool outside =
            b.x1 < outline.x0 || b.x0 > outline.x1 || b.y1 < outline.y0 || b.y0 > outline.y1;
        CHECK(outside);
        CHECK(pinmask::test::is_simple(r));
        CHECK(doubled_area(r) > 0);
        boxes.push_back(b);
    }
    // Crosses first (12 vertices), then bars (rectangles): bounding boxes pairwise separated.
    for (std::size_t i = 0; i < boxes.size(); ++i)
        for (std::size_t j = i + 1; j < boxes.size(); ++j) {
            const BoxNm &a = boxes[i], &b = boxes[j];
            const bool apart = a.x1 < b.x0 || b.x1 < a.x0 || a.y1 < b.y0 || b.y1 < a.y0;
            INFO("annotations " << i << " and " << j);
            CHECK(apart);
        }
    CHECK(l.extent.y0 < outline.y0);
    CHECK(label_text("mask_01.b+") == "MASK_01.B+");
    CHECK(label_text("a#b") == "A-B");
}

TEST_CASE("invalid options and empty masks are refused with InvalidInput") {
    Mask empty = golden_mask();
    empty.pattern.pinholes.clear();
    CHECK_THROWS_AS(make_layout(empty, {}), InvalidInput);
    CHECK_THROWS_AS(make_layout(golden_mask(), LayoutOptions{.grid_m = 1.5e-9}), InvalidInput);
    CHECK_THROWS_AS(make_layout(golden_mask(), LayoutOptions{.grid_m = 0}), InvalidInput);
    CHECK_THROWS_AS(make_layout(golden_mask(), LayoutOptions{.hole_side_m = 500e-6}), InvalidInput);
    CHECK_THROWS_AS(make_layout(golden_mask(), LayoutOptions{.frame_m = -1e-3}), InvalidInput);
    // Regression (bad-input corpus): a 1 nm hole on a 1000 nm grid snapped to zero-area squares
    // that were written with exit 0.
    CHECK_THROWS_WITH_AS(
        make_layout(golden_mask(), LayoutOptions{.hole_side_m = 1e-9, .grid_m = 1e-6}),
        doctest::Contains("2 grid steps"), InvalidInput);
    CHECK_NOTHROW(make_layout(golden_mask(), LayoutOptions{.hole_side_m = 2e-6, .grid_m = 1e-6}));
    LayoutOptions fine;
    fine.shape = HoleShape::kCircle;
    fine.chord_tolerance_m = 1e-15;
    CHECK_THROWS_AS(make_layout(golden_mask(), fine), InvalidInput);
    CHECK_THROWS_AS(parse_tone("grey", "--tone"), InvalidInput);
    CHECK_THROWS_AS(parse_hole_shape("star", "--shape"), InvalidInput);
    CHECK(parse_tone("dark", "--tone") == Tone::kDark);
}
