// The exact predicates of the design-rule check against independent formulations on random small
// integer geometry (where every reference below is exact too): segment contact by solving the
// two lines' parameters as fractions, point-to-segment distance by Lagrange's identity
// (|w|^2 |d|^2 - (w.d)^2 instead of the cross product), point in ring by the winding angle.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "export/layout/segment_predicates.hpp"

using namespace pinmask;

namespace {

constexpr int kTrials = 20000;
constexpr int kCoord = 6;  // coordinates in -6..6: many touching, collinear and parallel cases

// Closed segments ab, cd meet: a + s (b - a) = c + t (d - c) with s, t in [0, 1], as fractions;
// parallel segments meet when collinear with overlapping extents.
bool meet_reference(PointNm a, PointNm b, PointNm c, PointNm d) {
    const long long rx = b.x - a.x, ry = b.y - a.y, qx = d.x - c.x, qy = d.y - c.y;
    const long long wx = c.x - a.x, wy = c.y - a.y;
    const long long den = rx * qy - ry * qx;
    if (den != 0) {
        long long sn = wx * qy - wy * qx, tn = wx * ry - wy * rx, dd = den;
        if (dd < 0) sn = -sn, tn = -tn, dd = -dd;
        return 0 <= sn && sn <= dd && 0 <= tn && tn <= dd;
    }
    if (wx * ry - wy * rx != 0) return false;  // parallel, not collinear
    // Collinear (or degenerate): compare extents on both axes.
    auto overlap = [](long long a0, long long a1, long long b0, long long b1) {
        return std::max(std::min(a0, a1), std::min(b0, b1)) <=
               std::min(std::max(a0, a1), std::max(b0, b1));
    };
    const bool degenerate_ab = rx == 0 && ry == 0, degenerate_cd = qx == 0 && qy == 0;
    if (degenerate_ab && degenerate_cd) return a.x == c.x && a.y == c.y;
    if (degenerate_cd) {  // c on the line of ab: within its extent
        return overlap(a.x, b.x, c.x, c.x) && overlap(a.y, b.y, c.y, c.y);
    }
    if (degenerate_ab && (a.x - c.x) * qy - (a.y - c.y) * qx != 0) return false;
    return overlap(a.x, b.x, c.x, d.x) && overlap(a.y, b.y, c.y, d.y);
}

// |p - segment ab|^2 < g2 by Lagrange's identity: the squared distance to the line is
// (|w|^2 |d|^2 - (w.d)^2) / |d|^2 where the foot falls inside the segment.
bool closer_reference(PointNm p, PointNm a, PointNm b, long long g2) {
    const long long dx = b.x - a.x, dy = b.y - a.y, wx = p.x - a.x, wy = p.y - a.y;
    const long long dot = dx * wx + dy * wy, len2 = dx * dx + dy * dy;
    const long long ex = p.x - b.x, ey = p.y - b.y;
    if (len2 == 0 || dot <= 0) return wx * wx + wy * wy < g2;
    if (dot >= len2) return ex * ex + ey * ey < g2;
    return (wx * wx + wy * wy) * len2 - dot * dot < g2 * len2;
}

PointNm random_point(std::mt19937_64& rng) {
    std::uniform_int_distribution<int> u(-kCoord, kCoord);
    return {u(rng), u(rng)};
}

}  // namespace

TEST_CASE("segments_meet equals the parametric solution") {
    std::mt19937_64 rng(7);
    int meeting = 0;
    for (int i = 0; i < kTrials; ++i) {
        const PointNm a = random_point(rng), b = random_point(rng), c = random_point(rng),
                      d = random_point(rng);
        const bool expected = meet_reference(a, b, c, d);
        INFO(a.x << "," << a.y << " " << b.x << "," << b.y << " / " << c.x << "," << c.y << " "
                 << d.x << "," << d.y);
        CHECK(segments_meet(a, b, c, d) == expected);
        meeting += expected;
    }
    CHECK(meeting > kTrials / 10);  // both outcomes are exercised
    CHECK(meeting < kTrials * 9 / 10);
}

TEST_CASE("point_closer and segments_closer equal Lagrange's identity") {
    std::mt19937_64 rng(8);
    std::uniform_int_distribution<int> g(0, 40);
    for (int i = 0; i < kTrials; ++i) {
        const PointNm p = random_point(rng), a = random_point(rng), b = random_point(rng),
                      c = random_point(rng);
        const long long g2 = g(rng);
        CHECK(point_closer(p, a, b, g2) == closer_reference(p, a, b, g2));
        const bool expected = meet_reference(a, b, p, c) || closer_reference(a, p, c, g2) ||
                              closer_reference(b, p, c, g2) || closer_reference(p, a, b, g2) ||
                              closer_reference(c, a, b, g2);
        CHECK(segments_closer(a, b, p, c, g2) == expected);
    }
}

TEST_CASE("point_inside equals the winding angle on star-shaped rings") {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
    std::uniform_int_distribution<int> radius(2, 40), vertices(3, 12);
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
        // Vertices at sorted angles around the origin: a simple (star-shaped) ring.
        std::vector<double> angles(static_cast<std::size_t>(vertices(rng)));
        for (double& t : angles) t = angle(rng);
        std::sort(angles.begin(), angles.end());
        Ring r;
        for (double t : angles) {
            const PointNm v{std::llround(radius(rng) * std::cos(t)),
                            std::llround(radius(rng) * std::sin(t))};
            if (r.empty() || v.x != r.back().x || v.y != r.back().y) r.push_back(v);
        }
        std::uniform_int_distribution<int> u(-45, 45);
        for (int k = 0; k < 20; ++k) {
            const PointNm p{u(rng), u(rng)};
            bool on_boundary = false;
            double winding = 0.0;
            for (std::size_t j = 0; j < r.size(); ++j) {
                const PointNm& a = r[j];
                const PointNm& b = r[(j + 1) % r.size()];
                on_boundary = on_boundary || point_closer(p, a, b, 1);  // distance 0
                winding +=
                    std::atan2(double(cross(p, a, b)), double(a.x - p.x) * double(b.x - p.x) +
                                                           double(a.y - p.y) * double(b.y - p.y));
            }
            if (on_boundary) continue;  // "strictly inside" is not defined there
            const bool expected = std::fabs(winding) > std::numbers::pi;
            CHECK(point_inside(p, r) == expected);
            inside += expected;
        }
    }
    CHECK(inside > 100);
}
