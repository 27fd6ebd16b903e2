// Design-rule check of exported mask geometry (rings in integer nanometres,
// export/layout/layout.hpp). Every verdict is exact: vertices are integers, and distances are
// compared squared in 128-bit integer arithmetic (coordinates within +-kMaxCoordNm,
// export/layout/xor_area.hpp); only the reported measurements are rounded to double. Rules
// (DrcRule, named by the one table drc_rule_name):
//   ring              fewer than 3 vertices
//   vertices          more than max_vertices vertices (GDSII record limits,
//   export/layout/vendor_rules) self_intersection not a simple polygon (CGAL::is_simple_2):
//   crossing or touching edges,
//                     repeated vertices (e.g. the closing vertex repeated), zero area
//   orientation       clockwise ring (every ring must be counter-clockwise)
//   area              a vertex outside the allowed area
//   feature           width below min_feature_nm: the distance between two non-adjacent edges
//                     of one ring that face each other across its interior (outward normals
//                     more than 90 degrees apart, each edge on the interior side of the other).
//                     For rectangles this is the shorter side; for rectilinear shapes the
//                     narrowest bar. Not measured: triangles (all edges adjacent), acute tips.
//   gap               distinct polygons closer than min_gap_nm (edge-to-edge, Euclidean), or a
//                     notch of one ring (facing edges with the exterior between them) narrower
//                     than min_gap_nm (reported with polygon_a = polygon_b = that ring)
//   touching          distinct polygons whose boundaries meet without overlapping interiors
//   overlap           distinct polygons whose interiors overlap (incl. one inside the other)
//   spacing           polygon centroids closer than min_center_spacing_nm (the mask's spacing
//                     rule, measured in the plane of the tiled mask, where the tiling makes the
//                     torus rule visible as plain distances)
// Candidate pairs come from CGAL's box-intersection sweep, so ~100k squares take about a second.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "design/optics/fab_grid.hpp"
#include "design/pattern/mask.hpp"
#include "export/layout/layout.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/layout/xor_area.hpp"

namespace pinmask {

// kCentroidToleranceNm (design/optics/fab_grid): a pair counts as too close only when short by
// more.

enum class DrcRule {
    kRing,
    kVertices,
    kSelfIntersection,
    kOrientation,
    kArea,
    kFeature,
    kOverlap,
    kTouching,
    kGap,
    kSpacing
};
inline constexpr std::size_t kDrcRuleCount = 10;

// The rule's name as reports, counts and JSON spell it ("self_intersection", ...), and the unit
// of its measured value and limit ("vertices" for ring and vertices, else "nm").
std::string drc_rule_name(DrcRule rule);
std::string drc_rule_unit(DrcRule rule);

struct DrcRules {
    double min_center_spacing_nm = 0.0;  // 0: not checked
    std::int64_t min_gap_nm = 1;         // >= 1 (touching is always a violation)
    std::int64_t min_feature_nm = 0;     // 0: not checked
    std::size_t max_vertices = kGdsHardMaxVertices;
    std::optional<BoxNm> allowed_area;  // unset: run_drc(Layout) uses the layout's areas
    double spacing_tolerance_nm = kCentroidToleranceNm;
    std::size_t max_reported_per_rule = 100;  // further violations are counted, not listed
};

inline constexpr std::size_t kNoPolygon = std::numeric_limits<std::size_t>::max();

struct DrcViolation {
    DrcRule rule = DrcRule::kRing;
    std::string message;                 // for people: polygons, measured value and limit in um
    PointNm where;                       // location of the problem
    std::size_t polygon_a = kNoPolygon;  // index of the polygon(s) involved
    std::size_t polygon_b = kNoPolygon;
    double value = 0.0;  // measured: nm for distances, a count for `vertices`
    double limit = 0.0;  // the rule's limit in the same unit
};

// Smallest values seen. Pairs are examined only near the rule's limit, so +inf means "nothing
// closer than the search radius" (about the rule), not "no neighbour at all".
struct DrcMeasured {
    double min_center_spacing_nm = std::numeric_limits<double>::infinity();
    double min_gap_nm = std::numeric_limits<double>::infinity();
    double min_feature_nm = std::numeric_limits<double>::infinity();
};

struct DrcReport {
    std::vector<DrcViolation> violations;       // at most max_reported_per_rule per rule
    std::map<std::string, std::size_t> counts;  // drc_rule_name -> violations found
    bool truncated = false;  // the pair scan stopped early (a flood of violations)
    std::size_t polygons_checked = 0;
    DrcMeasured measured;
    bool clean() const { return counts.empty() && !truncated; }
};

// Checks `polygons` (all of them take part in every rule; the area rule only if allowed_area
// is set). Throws InvalidInput for rules out of range or coordinates beyond +-kMaxCoordNm.
DrcReport run_drc(const std::vector<Ring>& polygons, const DrcRules& rules);

// Checks a layout: polygons and annotations together for the geometric rules, indices in
// violations counting polygons first, then annotations (index - polygons.size()). The spacing
// rule applies to clear-tone polygons only. Dark tone: the polygons are opaque pieces that may
// share edges (pairs of pieces are not checked, nor their widths); the clear regions they
// leave (the holes of their union, export/layout/xor_area union_holes) are checked as pinholes
// (spacing, width, gaps between them; no vertex limit: they are not drawn) and reported after
// the annotations. Without an allowed_area, clear-tone polygons and the clear regions must lie
// in active_area, dark-tone pieces (which include the frame) and annotations in extent.
DrcReport run_drc(const Layout& layout, const DrcRules& rules);

// Rules for a mask made at a vendor: centre spacing = min_spacing_cells * P, P the pinhole side
// on the fabrication grid (design/optics/fab_grid pitch_on_grid_nm: the pitch the layout uses, so
// the rule is evaluated on the same integers in generate, export and check), gap, feature and
// vertex limits from the vendor.
DrcRules rules_for_mask(const Mask& mask, const VendorRules& vendor,
                        std::int64_t grid_nm = kDefaultFabGridNm);

// The spacing rule on the design's own pinholes, before the layout merges touching ones (merged,
// two too-close pinholes become one polygon, and the polygon-level rule above cannot see them):
// when `report` holds no spacing violation, each pair of spacing_violations(mask.pattern) is
// added, its distance in nm on the pitch `pitch_nm` (the fabrication grid's; see
// rules_for_mask). A no-op when rules.min_center_spacing_nm is 0 (the rule is off).
void add_pattern_spacing(DrcReport& report, const Mask& mask, std::int64_t pitch_nm,
                         const DrcRules& rules);

}  // namespace pinmask
