#include "export/pipeline/drc.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/errors/name_table.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/layout/segment_predicates.hpp"
#include "export/layout/xor_area.hpp"

namespace pinmask {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;

// Limits of the rules: squared distances stay inside Int128 (see the file comment of drc.hpp).
constexpr std::int64_t kMaxRuleNm = std::int64_t{1} << 31;
// Polygons up to this many vertices have their width checked over all edge pairs; larger ones
// go through the box-intersection sweep over their edges.
constexpr std::size_t kBruteForceVertices = 64;
// Self-intersections are located by an O(V^2) search up to this size, else reported at vertex 0.
constexpr std::size_t kLocateVertices = 512;
// A flood of pair violations (e.g. thousands of copies of one polygon) stops the scan here.
constexpr std::size_t kMaxPairViolations = 100'000;

// The one name table of the rules, in report order (the enum's order).
struct RuleName {
    DrcRule rule;
    const char* name;
    const char* unit;
};
constexpr std::array<RuleName, kDrcRuleCount> kRuleNames = {{
    {DrcRule::kRing, "ring", "vertices"},
    {DrcRule::kVertices, "vertices", "vertices"},
    {DrcRule::kSelfIntersection, "self_intersection", "nm"},
    {DrcRule::kOrientation, "orientation", "nm"},
    {DrcRule::kArea, "area", "nm"},
    {DrcRule::kFeature, "feature", "nm"},
    {DrcRule::kOverlap, "overlap", "nm"},
    {DrcRule::kTouching, "touching", "nm"},
    {DrcRule::kGap, "gap", "nm"},
    {DrcRule::kSpacing, "spacing", "nm"},
}};
const RuleName& rule_entry(DrcRule rule) {
    const auto i = static_cast<std::size_t>(rule);
    if (i >= kRuleNames.size() || kRuleNames[i].rule != rule)
        throw RuntimeFailure("DRC rule table out of order");  // a programming error
    return kRuleNames[i];
}
std::size_t rule_rank(DrcRule rule) { return static_cast<std::size_t>(rule); }

struct StopScan {};

std::string um(double nm) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.3f um", nm * 1e-3);
    return buf;
}
std::string at_um(double x_nm, double y_nm) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "(%.3f, %.3f) um", x_nm * 1e-3, y_nm * 1e-3);
    return buf;
}
PointNm to_point(double x, double y) { return {std::llround(x), std::llround(y)}; }

struct RingInfo {
    bool usable = false;  // >= 3 vertices, no repeated closing vertex: takes part in pair rules
    bool simple = false;
    int orientation = 0;  // +1 counter-clockwise, -1 clockwise, 0 unknown
    double cx = 0, cy = 0;
    std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Where a ring comes from. Pairs are checked between polygons and annotations of any kind,
// except: dark-tone pieces tile the opaque area (they may share edges with each other and with
// the clear regions they leave), and clear regions are compared only with each other.
enum class Group { kPolygon, kAnnotation, kPiece, kClearRegion };
const char* group_name(Group g) {
    static constexpr NameTable<Group, 4> kNames{{{Group::kPolygon, "polygon"},
                                                 {Group::kAnnotation, "annotation"},
                                                 {Group::kPiece, "piece"},
                                                 {Group::kClearRegion, "clear region"}}};
    return name_or(kNames, g, "?");
}
bool pair_checked(Group a, Group b) {
    if (a == Group::kPiece || b == Group::kPiece) {
        return a == Group::kAnnotation || b == Group::kAnnotation;
    }
    if (a == Group::kClearRegion || b == Group::kClearRegion) return a == b;
    return true;
}

// One ring to check: the box it must stay in, whether it is a pinhole for the spacing rule and
// whether its own width and notches are checked (not for pieces of a tiling).
struct DrcItem {
    const Ring* ring = nullptr;
    std::optional<BoxNm> area;
    bool spacing = false;
    bool own_shape = true;
    Group group = Group::kPolygon;
    std::size_t index = 0;  // within its group
};
using DrcInput = std::vector<DrcItem>;

class Checker {
  public:
    Checker(const DrcInput& in, const DrcRules& rules) : in_(in), rules_(rules) {}
    DrcReport run();

  private:
    std::string name(std::size_t i) const {
        return std::string(group_name(in_[i].group)) + " " + std::to_string(in_[i].index);
    }
    const Ring& ring(std::size_t i) const { return *in_[i].ring; }
    void add(DrcRule rule, const std::string& message, PointNm where, std::size_t a, std::size_t b,
             double value, double limit);
    void check_ring(std::size_t i);
    void check_width(std::size_t i);
    void check_edge_pair(std::size_t i, std::size_t e, std::size_t f);
    void check_pair(std::size_t i, std::size_t j);
    void check_spacing();

    const DrcInput& in_;
    const DrcRules& rules_;
    std::vector<RingInfo> info_;
    DrcReport report_;
    std::vector<DrcViolation> found_;
    std::map<DrcRule, std::size_t> stored_;
    bool pair_stage_ = false;
    std::size_t pair_found_ = 0;
};

void Checker::add(DrcRule rule, const std::string& message, PointNm where, std::size_t a,
                  std::size_t b, double value, double limit) {
    ++report_.counts[drc_rule_name(rule)];
    // Pairs arrive in sweep order: keep them all (up to the flood limit), sort, then trim.
    if (pair_stage_) {
        if (++pair_found_ > kMaxPairViolations) throw StopScan{};
    } else if (stored_[rule]++ >= rules_.max_reported_per_rule) {
        return;
    }
    found_.push_back({rule, message, where, a, b, value, limit});
}

void Checker::check_ring(std::size_t i) {
    const Ring& r = ring(i);
    RingInfo& info = info_[i];
    const std::size_t n = r.size();
    if (n < 3) {
        add(DrcRule::kRing, name(i) + ": " + std::to_string(n) + " vertices; a polygon needs >= 3",
            n ? r.front() : PointNm{}, i, kNoPolygon, double(n), 3);
        return;
    }
    info.usable = true;
    info.x0 = info.x1 = r[0].x;
    info.y0 = info.y1 = r[0].y;
    for (const PointNm& p : r) {
        info.x0 = std::min(info.x0, p.x), info.x1 = std::max(info.x1, p.x);
        info.y0 = std::min(info.y0, p.y), info.y1 = std::max(info.y1, p.y);
    }
    // Clear regions are derived, not drawn: no file carries them, so no vertex limit applies.
    if (n > rules_.max_vertices && in_[i].group != Group::kClearRegion) {
        add(DrcRule::kVertices,
            name(i) + ": " + std::to_string(n) + " vertices, limit " +
                std::to_string(rules_.max_vertices),
            r.front(), i, kNoPolygon, double(n), double(rules_.max_vertices));
    }
    // Signed area (twice) exactly, and the centroid relative to vertex 0 in long double.
    Int128 area2 = 0;
    long double sx = 0, sy = 0;
    for (std::size_t k = 1; k + 1 < n; ++k) {
        const Int128 c = cross(r[0], r[k], r[k + 1]);
        area2 += c;
        sx += static_cast<long double>(c) * ((r[k].x - r[0].x) + (r[k + 1].x - r[0].x));
        sy += static_cast<long double>(c) * ((r[k].y - r[0].y) + (r[k + 1].y - r[0].y));
    }
    if (area2 != 0) {
        info.cx = double(r[0].x + sx / (3.0L * static_cast<long double>(area2)));
        info.cy = double(r[0].y + sy / (3.0L * static_cast<long double>(area2)));
    } else {
        info.cx = 0.5 * (double(info.x0) + double(info.x1));
        info.cy = 0.5 * (double(info.y0) + double(info.y1));
    }
    std::vector<Epick::Point_2> pts;
    pts.reserve(n);
    for (const PointNm& p : r) pts.emplace_back(double(p.x), double(p.y));  // exact: |x| <= 2^30
    info.simple = CGAL::is_simple_2(pts.begin(), pts.end(), Epick());
    if (!info.simple) {
        PointNm where = r.front();
        bool located = false;
        for (std::size_t e = 0; e < n && n <= kLocateVertices && !located; ++e) {
            for (std::size_t f = e + 2; f < n && !located; ++f) {
                if (e == 0 && f == n - 1) continue;  // adjacent through the closing edge
                const PointNm &a = r[e], &b = r[(e + 1) % n], &c = r[f], &d = r[(f + 1) % n];
                if (!segments_meet(a, b, c, d)) continue;
                const Approach t = segment_approach(a, b, c, d);
                where = to_point(t.x, t.y);
                located = true;
            }
        }
        const std::string why = r.front() == r.back()
                                    ? " (the last vertex repeats the first; rings close implicitly)"
                                : area2 == 0 ? " (zero area)"
                                             : "";
        add(DrcRule::kSelfIntersection,
            name(i) + ": not a simple polygon (edges cross or touch) near " +
                at_um(double(where.x), double(where.y)) + why,
            where, i, kNoPolygon, 0, 0);
    } else {
        info.orientation = area2 > 0 ? 1 : -1;
        if (area2 < 0) {
            add(DrcRule::kOrientation, name(i) + ": clockwise; rings must be counter-clockwise",
                r.front(), i, kNoPolygon, 0, 0);
        }
    }
    if (const auto& box = in_[i].area) {
        for (const PointNm& p : r) {
            if (p.x >= box->x0 && p.x <= box->x1 && p.y >= box->y0 && p.y <= box->y1) continue;
            add(DrcRule::kArea,
                name(i) + ": vertex " + at_um(double(p.x), double(p.y)) + " outside the area " +
                    at_um(double(box->x0), double(box->y0)) + " - " +
                    at_um(double(box->x1), double(box->y1)),
                p, i, kNoPolygon, 0, 0);
            break;
        }
    }
    if (info.simple && in_[i].own_shape) check_width(i);
}

// Width (edges facing across the interior) and notch (facing across the exterior) of edges e, f
// of ring i; e and f are not adjacent.
void Checker::check_edge_pair(std::size_t i, std::size_t e, std::size_t f) {
    const Ring& r = ring(i);
    const std::size_t n = r.size();
    const PointNm &a = r[e], &b = r[(e + 1) % n], &c = r[f], &d = r[(f + 1) % n];
    if (Int128(b.x - a.x) * (d.x - c.x) + Int128(b.y - a.y) * (d.y - c.y) >= 0) return;
    const int o = info_[i].orientation;  // interior is on the left of CCW edges
    const int s1 = o * sign(cross(a, b, c)), s2 = o * sign(cross(a, b, d));
    const int t1 = o * sign(cross(c, d, a)), t2 = o * sign(cross(c, d, b));
    const bool interior = s1 >= 0 && s2 >= 0 && t1 >= 0 && t2 >= 0 && s1 + s2 > 0 && t1 + t2 > 0;
    const bool exterior = s1 <= 0 && s2 <= 0 && t1 <= 0 && t2 <= 0 && s1 + s2 < 0 && t1 + t2 < 0;
    if (interior) {
        const Approach t = segment_approach(a, b, c, d);
        report_.measured.min_feature_nm = std::min(report_.measured.min_feature_nm, t.dist);
        const Int128 f2 = Int128(rules_.min_feature_nm) * rules_.min_feature_nm;
        if (rules_.min_feature_nm > 0 && segments_closer(a, b, c, d, f2)) {
            add(DrcRule::kFeature,
                name(i) + ": width " + um(t.dist) + " < " + um(double(rules_.min_feature_nm)) +
                    " at " + at_um(t.x, t.y),
                to_point(t.x, t.y), i, kNoPolygon, t.dist, double(rules_.min_feature_nm));
        }
    } else if (exterior) {
        const Int128 g2 = Int128(rules_.min_gap_nm) * rules_.min_gap_nm;
        if (!segments_closer(a, b, c, d, g2)) return;
        const Approach t = segment_approach(a, b, c, d);
        report_.measured.min_gap_nm = std::min(report_.measured.min_gap_nm, t.dist);
        add(DrcRule::kGap,
            name(i) + ": notch " + um(t.dist) + " wide < " + um(double(rules_.min_gap_nm)) +
                " at " + at_um(t.x, t.y),
            to_point(t.x, t.y), i, i, t.dist, double(rules_.min_gap_nm));
    }
}

void Checker::check_width(std::size_t i) {
    const Ring& r = ring(i);
    const std::size_t n = r.size();
    const auto adjacent = [n](std::size_t e, std::size_t f) {
        return e == f || (e + 1) % n == f || (f + 1) % n == e;
    };
    if (n <= kBruteForceVertices) {
        for (std::size_t e = 0; e < n; ++e) {
            for (std::size_t f = e + 1; f < n; ++f) {
                if (!adjacent(e, f)) check_edge_pair(i, e, f);
            }
        }
        return;
    }
    // Edge boxes grown by half the search radius meet when the edges may be closer than it.
    const double half = 0.5 * double(std::max(rules_.min_feature_nm, rules_.min_gap_nm));
    std::vector<Box> boxes;
    boxes.reserve(n);
    for (std::size_t e = 0; e < n; ++e) {
        const PointNm &a = r[e], &b = r[(e + 1) % n];
        boxes.emplace_back(
            CGAL::Bbox_2(double(std::min(a.x, b.x)) - half, double(std::min(a.y, b.y)) - half,
                         double(std::max(a.x, b.x)) + half, double(std::max(a.y, b.y)) + half),
            e);
    }
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& p, const Box& q) {
        const std::size_t e = std::min(p.info(), q.info()), f = std::max(p.info(), q.info());
        if (!adjacent(e, f)) pairs.emplace_back(e, f);
    });
    std::sort(pairs.begin(), pairs.end());
    for (const auto& [e, f] : pairs) check_edge_pair(i, e, f);
}

// Distinct rings i < j whose boxes, grown by half the gap, meet.
void Checker::check_pair(std::size_t i, std::size_t j) {
    const RingInfo &p = info_[i], &q = info_[j];
    const Int128 g2 = Int128(rules_.min_gap_nm) * rules_.min_gap_nm;
    const Int128 bx = std::max<std::int64_t>({0, q.x0 - p.x1, p.x0 - q.x1});
    const Int128 by = std::max<std::int64_t>({0, q.y0 - p.y1, p.y0 - q.y1});
    if (bx * bx + by * by >= g2) return;  // boxes (hence polygons) at least the gap apart
    const Ring &r = ring(i), &s = ring(j);
    bool contact = false;
    Approach best;
    for (std::size_t e = 0; e < r.size(); ++e) {
        const PointNm &a = r[e], &b = r[(e + 1) % r.size()];
        for (std::size_t f = 0; f < s.size(); ++f) {
            const PointNm &c = s[f], &d = s[(f + 1) % s.size()];
            const bool meet = segments_meet(a, b, c, d);
            const Approach t = segment_approach(a, b, c, d);
            if (meet) {  // the first contact found is the reported location
                contact = true;
                best = t;
                best.dist = 0;
                break;
            }
            if (t.dist < best.dist) best = t;
        }
        if (contact) break;
    }
    report_.measured.min_gap_nm = std::min(report_.measured.min_gap_nm, best.dist);
    const std::string pair = name(i) + " and " + name(j);
    if (contact) {
        DrcRule rule = DrcRule::kTouching;
        std::string note;
        if (p.simple && q.simple) {
            if (intersection_area_nm2({r}, {s}) > 0) rule = DrcRule::kOverlap;
        } else {
            note = " (overlap not classified: not simple)";
        }
        add(rule,
            pair + (rule == DrcRule::kOverlap ? " overlap" : " touch") + " at " +
                at_um(best.x, best.y) + note,
            to_point(best.x, best.y), i, j, 0, double(rules_.min_gap_nm));
        return;
    }
    const bool s_in_r = point_inside(s[0], r), r_in_s = !s_in_r && point_inside(r[0], s);
    if (s_in_r || r_in_s) {
        const PointNm where = s_in_r ? s[0] : r[0];
        report_.measured.min_gap_nm = 0;
        add(DrcRule::kOverlap,
            pair + " overlap: " + name(s_in_r ? j : i) + " lies inside " + name(s_in_r ? i : j) +
                " at " + at_um(double(where.x), double(where.y)),
            where, i, j, 0, double(rules_.min_gap_nm));
        return;
    }
    for (std::size_t e = 0; e < r.size(); ++e) {
        for (std::size_t f = 0; f < s.size(); ++f) {
            if (!segments_closer(r[e], r[(e + 1) % r.size()], s[f], s[(f + 1) % s.size()], g2)) {
                continue;
            }
            add(DrcRule::kGap,
                pair + ": gap " + um(best.dist) + " < " + um(double(rules_.min_gap_nm)) + " at " +
                    at_um(best.x, best.y),
                to_point(best.x, best.y), i, j, best.dist, double(rules_.min_gap_nm));
            return;
        }
    }
}

// Centroid pairs closer than the rule: boxes of side s around the centroids meet (closed), so
// every pair within s (even exactly s apart along an axis) is examined.
void Checker::check_spacing() {
    const double s = rules_.min_center_spacing_nm;
    if (s <= 0) return;
    const double limit = s - rules_.spacing_tolerance_nm;
    std::vector<Box> boxes;
    for (std::size_t i = 0; i < info_.size(); ++i) {
        if (!info_[i].usable || !in_[i].spacing) continue;
        const RingInfo& p = info_[i];
        boxes.emplace_back(
            CGAL::Bbox_2(p.cx - 0.5 * s, p.cy - 0.5 * s, p.cx + 0.5 * s, p.cy + 0.5 * s), i);
    }
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& u, const Box& v) {
        const std::size_t i = std::min(u.info(), v.info()), j = std::max(u.info(), v.info());
        const RingInfo &p = info_[i], &q = info_[j];
        const double d = std::hypot(q.cx - p.cx, q.cy - p.cy);
        report_.measured.min_center_spacing_nm =
            std::min(report_.measured.min_center_spacing_nm, d);
        if (d >= limit) return;
        const double mx = 0.5 * (p.cx + q.cx), my = 0.5 * (p.cy + q.cy);
        add(DrcRule::kSpacing,
            name(i) + " and " + name(j) + ": centres " + um(d) + " apart < " + um(s) + " at " +
                at_um(mx, my),
            to_point(mx, my), i, j, d, s);
    });
}

DrcReport Checker::run() {
    const std::size_t n = in_.size();
    report_.polygons_checked = n;
    info_.assign(n, {});
    // The time budget (PINMASK_TIME_LIMIT) inside `check`: a no-op elsewhere.
    TimeLimitPoll poll_rings("the design-rule check (rings)");
    for (std::size_t i = 0; i < n; ++i) {
        poll_rings();
        check_ring(i);
    }
    check_time_limit("the design-rule check (after the rings)");
    TimeLimitPoll poll_pairs("the design-rule check (pairs)");
    pair_stage_ = true;
    try {
        const double half = 0.5 * double(rules_.min_gap_nm);
        std::vector<Box> boxes;
        for (std::size_t i = 0; i < n; ++i) {
            const RingInfo& p = info_[i];
            if (!p.usable) continue;
            boxes.emplace_back(CGAL::Bbox_2(double(p.x0) - half, double(p.y0) - half,
                                            double(p.x1) + half, double(p.y1) + half),
                               i);
        }
        CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& u, const Box& v) {
            poll_pairs();
            if (!pair_checked(in_[u.info()].group, in_[v.info()].group)) return;
            check_pair(std::min(u.info(), v.info()), std::max(u.info(), v.info()));
        });
        check_spacing();
    } catch (const StopScan&) {
        report_.truncated = true;
    }
    std::stable_sort(found_.begin(), found_.end(),
                     [](const DrcViolation& x, const DrcViolation& y) {
                         const auto rx = rule_rank(x.rule), ry = rule_rank(y.rule);
                         if (rx != ry) return rx < ry;
                         return x.polygon_a != y.polygon_a ? x.polygon_a < y.polygon_a
                                                           : x.polygon_b < y.polygon_b;
                     });
    std::map<DrcRule, std::size_t> kept;
    for (DrcViolation& v : found_) {
        if (kept[v.rule]++ < rules_.max_reported_per_rule)
            report_.violations.push_back(std::move(v));
    }
    return std::move(report_);
}

void validate_rules(const DrcRules& r) {
    if (r.min_gap_nm < 1 || r.min_gap_nm > kMaxRuleNm) {
        throw invalid_field("min_gap_nm", std::to_string(r.min_gap_nm),
                            "must be between 1 and " + std::to_string(kMaxRuleNm));
    }
    if (r.min_feature_nm < 0 || r.min_feature_nm > kMaxRuleNm) {
        throw invalid_field("min_feature_nm", std::to_string(r.min_feature_nm),
                            "must be between 0 and " + std::to_string(kMaxRuleNm));
    }
    if (!std::isfinite(r.min_center_spacing_nm) || r.min_center_spacing_nm < 0 ||
        r.min_center_spacing_nm > double(kMaxRuleNm)) {
        throw invalid_field("min_center_spacing_nm", std::to_string(r.min_center_spacing_nm),
                            "must be finite, between 0 and " + std::to_string(kMaxRuleNm));
    }
    if (!std::isfinite(r.spacing_tolerance_nm) || r.spacing_tolerance_nm < 0) {
        throw invalid_field("spacing_tolerance_nm", std::to_string(r.spacing_tolerance_nm),
                            "must be finite and >= 0");
    }
    if (r.max_vertices < 3) {
        throw invalid_field(field_ref("max_vertices"), std::to_string(r.max_vertices),
                            "must be >= 3");
    }
}

void validate_coordinates(const DrcInput& in) {
    for (const DrcItem& item : in) {
        for (const PointNm& p : *item.ring) {
            if (std::max(std::abs(p.x), std::abs(p.y)) <= kMaxCoordNm) continue;
            throw invalid_field(
                std::string(group_name(item.group)) + " " + std::to_string(item.index) + " vertex",
                std::to_string(p.x) + ", " + std::to_string(p.y) + " nm",
                "coordinates must be within +-" + std::to_string(kMaxCoordNm) + " nm");
        }
    }
}

DrcReport run_checked(const DrcInput& in, const DrcRules& rules) {
    validate_rules(rules);
    validate_coordinates(in);
    return Checker(in, rules).run();
}

}  // namespace

DrcReport run_drc(const std::vector<Ring>& polygons, const DrcRules& rules) {
    DrcInput in;
    for (std::size_t i = 0; i < polygons.size(); ++i) {
        in.push_back({&polygons[i], rules.allowed_area, true, true, Group::kPolygon, i});
    }
    return run_checked(in, rules);
}

DrcReport run_drc(const Layout& layout, const DrcRules& rules) {
    validate_rules(rules);
    const bool clear = layout.tone == Tone::kClear;
    const auto area = [&](const BoxNm& box) { return rules.allowed_area.value_or(box); };
    DrcInput in;
    for (std::size_t i = 0; i < layout.polygons.size(); ++i) {
        // Dark-tone pieces include the frame around the active area: they stay in the extent.
        in.push_back({&layout.polygons[i], area(clear ? layout.active_area : layout.extent), clear,
                      clear, clear ? Group::kPolygon : Group::kPiece, i});
    }
    for (std::size_t i = 0; i < layout.annotations.size(); ++i) {
        in.push_back(
            {&layout.annotations[i], area(layout.extent), false, true, Group::kAnnotation, i});
    }
    // Dark tone: the pinholes are the holes of the union of the pieces; they take the clear-tone
    // rules (spacing, width, and gaps between pinholes = width of the opaque web).
    std::vector<Ring> holes;
    if (!clear && !layout.polygons.empty()) {
        validate_coordinates(in);
        holes = union_holes(layout.polygons);
        for (std::size_t i = 0; i < holes.size(); ++i) {
            in.push_back({&holes[i], area(layout.active_area), true, true, Group::kClearRegion, i});
        }
    }
    return run_checked(in, rules);
}

std::string drc_rule_name(DrcRule rule) { return rule_entry(rule).name; }

std::string drc_rule_unit(DrcRule rule) { return rule_entry(rule).unit; }

void add_pattern_spacing(DrcReport& report, const Mask& mask, std::int64_t pitch_nm,
                         const DrcRules& rules) {
    if (!(rules.min_center_spacing_nm > 0.0)) return;
    const auto it = report.counts.find(drc_rule_name(DrcRule::kSpacing));
    if (it != report.counts.end() && it->second > 0) return;
    const std::vector<SpacingViolation> pairs = spacing_violations(mask.pattern);
    if (pairs.empty()) return;
    const double p = double(pitch_nm);
    report.counts[drc_rule_name(DrcRule::kSpacing)] += pairs.size();
    std::size_t stored = 0;
    for (const SpacingViolation& v : pairs) {
        if (stored++ >= rules.max_reported_per_rule) break;
        const double d = v.distance_cells * p;
        const auto cell = [](const Cell& c) {
            return "(" + std::to_string(c.row) + ", " + std::to_string(c.col) + ")";
        };
        DrcViolation x;
        x.rule = DrcRule::kSpacing;
        x.message = "pinholes " + cell(v.a) + " and " + cell(v.b) + " of the design: centres " +
                    um(d) + " apart < " + um(rules.min_center_spacing_nm) +
                    " (on the torus; the layout merges them into one polygon)";
        x.value = d;
        x.limit = rules.min_center_spacing_nm;
        report.violations.push_back(std::move(x));
    }
}

DrcRules rules_for_mask(const Mask& mask, const VendorRules& vendor, std::int64_t grid_nm) {
    DrcRules rules;
    const double pitch_nm = double(pitch_on_grid_nm(mask.camera.pinhole_m, grid_nm));
    rules.min_center_spacing_nm = mask.pattern.min_spacing_cells * pitch_nm;
    rules.min_gap_nm = vendor.min_gap_nm;
    rules.min_feature_nm = vendor.min_feature_nm;
    rules.max_vertices = vendor.max_vertices;
    return rules;
}

}  // namespace pinmask
