// Design-rule check: known-answer cases built by hand, and the pair rules against a direct
// O(P^2) reference on random layouts.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "export/pipeline/drc.hpp"

using namespace pinmask;

namespace {

Ring rect(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}
Ring square(std::int64_t x0, std::int64_t y0, std::int64_t side) {
    return rect(x0, y0, x0 + side, y0 + side);
}
DrcRules gap_rules(std::int64_t gap_nm) {
    DrcRules r;
    r.min_gap_nm = gap_nm;
    return r;
}
std::size_t count(const DrcReport& r, const std::string& rule) {
    const auto it = r.counts.find(rule);
    return it == r.counts.end() ? 0 : it->second;
}

}  // namespace

TEST_CASE("two squares exactly at the minimum gap pass, one nanometre closer fails") {
    const auto rules = gap_rules(16'000);
    CHECK(run_drc({square(0, 0, 440'000), square(456'000, 0, 440'000)}, rules).clean());
    const auto r = run_drc({square(0, 0, 440'000), square(455'999, 0, 440'000)}, rules);
    REQUIRE(r.violations.size() == 1);
    const auto& v = r.violations[0];
    CHECK(v.rule == DrcRule::kGap);
    CHECK(v.polygon_a == 0);
    CHECK(v.polygon_b == 1);
    CHECK(v.value == 15'999.0);
    CHECK(v.limit == 16'000.0);
    CHECK(v.where.x == 448'000);  // midway across the gap (rounded)
    CHECK(r.measured.min_gap_nm == 15'999.0);
}

TEST_CASE("a diagonal gap is Euclidean and exact: a 3-4-5 corner distance") {
    // Corner (1000, 1000) to corner (4000, 5000): exactly 5000 nm.
    const std::vector<Ring> p = {square(0, 0, 1000), square(4000, 5000, 1000)};
    CHECK(run_drc(p, gap_rules(5000)).clean());
    const auto r = run_drc(p, gap_rules(5001));
    CHECK(count(r, "gap") == 1);
}

TEST_CASE("touching and overlapping polygons are told apart") {
    const auto rules = gap_rules(1);
    const auto edge = run_drc({square(0, 0, 1000), square(1000, 200, 1000)}, rules);
    CHECK(count(edge, "touching") == 1);
    CHECK(count(edge, "overlap") == 0);
    const auto corner = run_drc({square(0, 0, 1000), square(1000, 1000, 1000)}, rules);
    REQUIRE(count(corner, "touching") == 1);
    CHECK(corner.violations[0].where == PointNm{1000, 1000});
    const auto overlap = run_drc({square(0, 0, 1000), square(500, 500, 1000)}, rules);
    CHECK(count(overlap, "overlap") == 1);
    CHECK(count(overlap, "touching") == 0);
    // One inside the other: boundaries never meet, still an overlap.
    const auto inside = run_drc({square(0, 0, 1000), square(200, 300, 100)}, rules);
    REQUIRE(count(inside, "overlap") == 1);
    CHECK(inside.violations[0].message.find("inside") != std::string::npos);
}

TEST_CASE("a bow-tie is not simple and is located at its crossing") {
    const Ring bowtie = {{0, 0}, {2000, 2000}, {2000, 0}, {0, 2000}};
    const auto r = run_drc({bowtie}, DrcRules{});
    REQUIRE(count(r, "self_intersection") == 1);
    CHECK(r.violations[0].where == PointNm{1000, 1000});
    // A repeated vertex also breaks simplicity.
    const Ring spur = {{0, 0}, {1000, 0}, {1000, 1000}, {1000, 0}, {0, 1000}};
    CHECK(count(run_drc({spur}, DrcRules{}), "self_intersection") == 1);
}

TEST_CASE("clockwise rings, explicitly closed rings and degenerate rings are reported") {
    const Ring ccw = square(0, 0, 1000);
    const Ring cw(ccw.rbegin(), ccw.rend());
    const auto r = run_drc({cw}, DrcRules{});
    REQUIRE(r.violations.size() == 1);
    CHECK(r.violations[0].rule == DrcRule::kOrientation);
    Ring closed = ccw;
    closed.push_back(ccw.front());
    const auto c = run_drc({closed}, DrcRules{});
    REQUIRE(count(c, "self_intersection") == 1);  // a repeated vertex
    CHECK(c.violations[0].message.find("repeats the first") != std::string::npos);
    // A zero-area ring (there and back along one line) is not simple either.
    CHECK(count(run_drc({Ring{{0, 0}, {1000, 0}, {2000, 0}, {1000, 0}}}, DrcRules{}),
                "self_intersection") == 1);
    CHECK(count(run_drc({Ring{{0, 0}, {5, 5}}}, DrcRules{}), "ring") == 1);
}

TEST_CASE("polygons outside the allowed area are reported with the offending vertex") {
    DrcRules rules;
    rules.allowed_area = BoxNm{0, 0, 10'000, 10'000};
    CHECK(run_drc({square(9000, 9000, 1000)}, rules).clean());  // on the border is inside
    const auto r = run_drc({square(9500, 2000, 1000)}, rules);
    REQUIRE(count(r, "area") == 1);
    CHECK(r.violations[0].where == PointNm{10'500, 2000});
}

TEST_CASE("vertex limits: a 200-gon breaks the GDS-friendly limit, not the hard one") {
    Ring circle;
    constexpr int kVertices = 200;
    for (int k = 0; k < kVertices; ++k) {
        const double t = 2.0 * M_PI * k / kVertices;
        circle.push_back({std::llround(1e6 * std::cos(t)), std::llround(1e6 * std::sin(t))});
    }
    DrcRules rules;
    rules.min_feature_nm = 16'000;  // a 2 mm disc is wide: its short edges must not count
    CHECK(run_drc({circle}, rules).clean());
    rules.max_vertices = kGdsFriendlyMaxVertices;
    const auto r = run_drc({circle}, rules);
    REQUIRE(r.violations.size() == 1);
    CHECK(r.violations[0].rule == DrcRule::kVertices);
    CHECK(r.violations[0].value == 200.0);
    CHECK(r.measured.min_feature_nm > 1.99e6);  // about the diameter
}

TEST_CASE("feature width: the short side of a bar, at the limit and one nm below") {
    DrcRules rules;
    rules.min_feature_nm = 10'000;
    CHECK(run_drc({rect(0, 0, 10'000, 100'000)}, rules).clean());
    const auto r = run_drc({rect(0, 0, 9'999, 100'000)}, rules);
    REQUIRE(count(r, "feature") == 1);
    CHECK(r.violations[0].value == 9'999.0);
}

TEST_CASE("combs: narrow teeth and narrow notches, brute-force and swept edge paths") {
    // A rectilinear comb: a spine 0..H plus `teeth` teeth of width w separated by notches of
    // width s. One tooth is 1 nm narrower, one notch 1 nm narrower.
    const auto comb = [](int teeth, std::int64_t w, std::int64_t s) {
        constexpr std::int64_t kSpine = 50'000, kTooth = 200'000;
        Ring r = {{0, 0}};
        std::int64_t x = 0;
        r.push_back({teeth * (w + s), 0});
        r.push_back({teeth * (w + s), kSpine});
        // Walk back along the top, right to left: notch then tooth.
        x = teeth * (w + s);
        for (int t = teeth - 1; t >= 0; --t) {
            const std::int64_t notch = (t == teeth / 2) ? s - 1 : s;
            const std::int64_t tooth = (t == teeth / 3) ? w - 1 : w;
            x -= notch;
            r.push_back({x, kSpine});
            r.push_back({x, kSpine + kTooth});
            x -= tooth;
            r.push_back({x, kSpine + kTooth});
            r.push_back({x, kSpine});
        }
        return r;
    };
    for (const int teeth : {3, 40}) {  // 14 vertices (all pairs) and 162 (box sweep)
        CAPTURE(teeth);
        DrcRules rules;
        rules.min_feature_nm = 20'000;
        rules.min_gap_nm = 16'000;
        rules.max_vertices = kGdsHardMaxVertices;
        const auto r = run_drc({comb(teeth, 20'000, 16'000)}, rules);
        CHECK(count(r, "feature") == 1);
        CHECK(count(r, "gap") == 1);
        CHECK(r.measured.min_feature_nm == 19'999.0);
        CHECK(r.measured.min_gap_nm == 15'999.0);
        CHECK(r.counts.size() == 2);
    }
}

TEST_CASE("centre spacing: exactly at the rule passes, a nanometre short fails") {
    DrcRules rules;
    rules.min_center_spacing_nm = 880'000;
    const std::int64_t d = 440'000;
    CHECK(run_drc({square(0, 0, d), square(880'000, 0, d), square(0, 880'000, d)}, rules).clean());
    const auto r = run_drc({square(0, 0, d), square(879'999, 0, d)}, rules);
    REQUIRE(count(r, "spacing") == 1);
    CHECK(r.violations[0].value == 879'999.0);
    // Diagonal neighbour of the 8-neighbourhood: sqrt(2) cells < 2 cells.
    CHECK(count(run_drc({square(0, 0, d), square(d, d, d)}, rules), "spacing") == 1);
}

TEST_CASE("pair rules agree with a direct O(P^2) reference on random squares") {
    std::mt19937_64 rng(7);
    for (const int grid : {11, 16, 31}) {
        CAPTURE(grid);
        // Squares of side 700 nm at random positions on a 1000 nm lattice, some jittered:
        // gaps, touches, overlaps and spacing violations all occur.
        std::uniform_int_distribution<int> cell(0, grid - 1), jitter(-400, 400);
        std::vector<Ring> p;
        std::set<std::pair<int, int>> used;
        for (int k = 0; k < grid * 2; ++k) {
            const int cx = cell(rng), cy = cell(rng);
            if (!used.insert({cx, cy}).second) continue;
            p.push_back(square(cx * 1000 + jitter(rng), cy * 1000 + jitter(rng), 700));
        }
        DrcRules rules;
        rules.min_gap_nm = 250;
        rules.min_center_spacing_nm = 1500;
        rules.max_reported_per_rule = 1'000'000;
        const auto r = run_drc(p, rules);
        // Reference for axis-aligned squares: the gap is the Euclidean distance of the boxes.
        std::size_t gap = 0, contact = 0, spacing = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            for (std::size_t j = i + 1; j < p.size(); ++j) {
                const auto dx =
                    std::max<std::int64_t>({0, p[j][0].x - p[i][2].x, p[i][0].x - p[j][2].x});
                const auto dy =
                    std::max<std::int64_t>({0, p[j][0].y - p[i][2].y, p[i][0].y - p[j][2].y});
                const auto d2 = dx * dx + dy * dy;
                if (d2 == 0)
                    ++contact;
                else if (d2 < rules.min_gap_nm * rules.min_gap_nm)
                    ++gap;
                const double cdx = double(p[j][0].x - p[i][0].x),
                             cdy = double(p[j][0].y - p[i][0].y);
                if (std::hypot(cdx, cdy) < rules.min_center_spacing_nm) ++spacing;
            }
        }
        CHECK(count(r, "gap") == gap);
        CHECK(count(r, "touching") + count(r, "overlap") == contact);
        CHECK(count(r, "spacing") == spacing);
        CHECK(gap + contact + spacing > 0);  // the case exercises the rules
    }
}

TEST_CASE("a flood of violations is counted in full and listed up to the cap") {
    std::vector<Ring> p(150, square(0, 0, 1000));
    DrcRules rules;
    rules.max_reported_per_rule = 10;
    const auto r = run_drc(p, rules);
    CHECK(count(r, "overlap") == 150 * 149 / 2);
    CHECK(r.violations.size() == 10);
    CHECK_FALSE(r.clean());
}

TEST_CASE("layouts: areas per set, annotations named, spacing only for clear tone") {
    Layout l;
    l.active_area = {0, 0, 2'000'000, 2'000'000};
    l.extent = {-1'000'000, -1'000'000, 3'000'000, 3'000'000};
    l.polygons = {square(0, 0, 440'000), square(440'000 * 2, 0, 440'000)};
    l.annotations = {square(-900'000, -900'000, 100'000)};  // outside active, inside extent
    DrcRules rules;
    rules.min_center_spacing_nm = 880'000;
    CHECK(run_drc(l, rules).clean());
    l.annotations.push_back(square(2'950'000, 0, 100'000));  // leaves the extent
    auto r = run_drc(l, rules);
    REQUIRE(count(r, "area") == 1);
    CHECK(r.violations[0].polygon_a == 3);
    CHECK(r.violations[0].message.find("annotation 1") != std::string::npos);
    l.annotations.pop_back();
    l.polygons.push_back(square(440'000, 880'000, 440'000));  // centres 880, 984, 984 um apart
    rules.min_center_spacing_nm = 1'000'000;
    CHECK(count(run_drc(l, rules), "spacing") == 3);
    l.tone = Tone::kDark;
    CHECK(count(run_drc(l, rules), "spacing") == 0);
}

TEST_CASE("rules from a mask and a vendor; bad rules and coordinates are invalid input") {
    Mask m;
    m.camera.pinhole_m = 440e-6;
    m.pattern.min_spacing_cells = 2.0;
    const auto rules = rules_for_mask(m, vendor_rules("film"));
    CHECK(rules.min_center_spacing_nm == 880'000.0);
    CHECK(rules.min_gap_nm == 16'000);
    CHECK(rules.min_feature_nm == 16'000);
    CHECK(vendor_rules("chrome").min_gap_nm == 1'000);
    CHECK_THROWS_WITH_AS(vendor_rules("glass"), doctest::Contains("film, chrome, none"),
                         InvalidInput);
    CHECK_THROWS_AS(run_drc({square(0, 0, 10)}, gap_rules(0)), InvalidInput);
    CHECK_THROWS_AS(run_drc({square(kMaxCoordNm, 0, 10)}, DrcRules{}), InvalidInput);
}

TEST_CASE("performance sanity: 100k pinholes of a tiled mask check clean") {
    // 317 x 317 = 100489 squares of side 440 um at pitch 880 um (spacing rule 2 cells, film
    // limits); the check must finish in seconds (no timing assertion).
    constexpr int kSide = 317;
    constexpr std::int64_t kD = 440'000;
    std::vector<Ring> p;
    p.reserve(kSide * kSide);
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) p.push_back(square(x * 2 * kD, y * 2 * kD, kD));
    }
    Mask m;
    const auto r = run_drc(p, rules_for_mask(m, vendor_rules("film")));
    CHECK(r.clean());
    CHECK(r.polygons_checked == p.size());
    CHECK(r.measured.min_center_spacing_nm == 880'000.0);
    CHECK(r.measured.min_feature_nm == 440'000.0);
}

TEST_CASE("dark tone: touching pieces are fine, the clear regions between them are checked") {
    // Outline 4000 x 4000 with two 1000 nm square holes 500 nm apart, drawn as five opaque
    // pieces sharing edges.
    Layout l;
    l.tone = Tone::kDark;
    l.active_area = {0, 0, 4000, 4000};
    l.extent = l.active_area;
    l.polygons = {rect(0, 0, 4000, 1000), rect(0, 2000, 4000, 4000), rect(0, 1000, 1000, 2000),
                  rect(2000, 1000, 2500, 2000), rect(3500, 1000, 4000, 2000)};
    DrcRules rules;
    rules.min_gap_nm = 500;
    rules.min_center_spacing_nm = 1500;
    rules.min_feature_nm = 1000;
    auto r = run_drc(l, rules);
    CHECK(r.clean());
    CHECK(r.polygons_checked == 7);  // five pieces and the two clear regions
    CHECK(r.measured.min_center_spacing_nm == 1500.0);
    rules.min_gap_nm = 501;
    rules.min_center_spacing_nm = 1501;
    rules.min_feature_nm = 1001;
    r = run_drc(l, rules);
    CHECK(count(r, "gap") == 1);
    CHECK(count(r, "spacing") == 1);
    CHECK(count(r, "feature") == 4);  // each region: width and height
    CHECK(r.violations.back().message.find("clear region 0 and clear region 1") !=
          std::string::npos);
    // The vertex limit applies to the drawn pieces only, not to the derived regions.
    rules = DrcRules{};
    rules.max_vertices = 3;
    CHECK(count(run_drc(l, rules), "vertices") == 5);
}

TEST_CASE("every DRC rule has one distinct name from the one table, in report order") {
    std::set<std::string> names;
    for (std::size_t i = 0; i < kDrcRuleCount; ++i) {
        const auto rule = static_cast<DrcRule>(i);
        const std::string name = drc_rule_name(rule);
        CHECK(!name.empty());
        names.insert(name);
        CHECK(drc_rule_unit(rule) ==
              (rule == DrcRule::kRing || rule == DrcRule::kVertices ? "vertices" : "nm"));
    }
    CHECK(names.size() == kDrcRuleCount);
    CHECK(drc_rule_name(DrcRule::kSelfIntersection) == "self_intersection");
    CHECK(drc_rule_name(DrcRule::kSpacing) == "spacing");
}
