#include "export/layout/dark_tone.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/shapes.hpp"

namespace pinmask {
namespace {

// Pieces of `box` above the upper chain of `hole` (left to right, strictly increasing x), plus
// the rectangles beside vertical end edges. Lower parts reuse this through a y reflection.
void upper_pieces(const BoxNm& b, const Ring& hole, std::size_t max_vertices,
                  std::vector<Ring>& out) {
    const std::size_t n = hole.size();
    std::int64_t xmin = hole[0].x, xmax = hole[0].x;
    for (const PointNm& p : hole) {
        xmin = std::min(xmin, p.x);
        xmax = std::max(xmax, p.x);
    }
    // Top vertices of the left and right extremes: the upper chain runs counter-clockwise
    // from the right one (r) to the left one (l).
    std::size_t l = 0, r = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (hole[i].x == xmin && (hole[l].x != xmin || hole[i].y > hole[l].y)) l = i;
        if (hole[i].x == xmax && (hole[r].x != xmax || hole[i].y > hole[r].y)) r = i;
    }
    Ring chain;  // left to right
    for (std::size_t i = l;; i = (i + n - 1) % n) {
        chain.push_back(hole[i]);
        if (i == r) break;
    }
    // Pieces: consecutive chain slices [a, c] sharing end vertices, closed upwards by vertical
    // cuts to the top edge; the first and last also reach the box's left and right edges.
    const std::size_t slice = max_vertices - 4;  // chain vertices per piece (+ <= 4 others)
    for (std::size_t a = 0; a + 1 < chain.size();) {
        const std::size_t c = std::min(chain.size() - 1, a + slice - 1);
        Ring piece;
        const bool first = a == 0, last = c == chain.size() - 1;
        if (first) piece.push_back({b.x0, chain[0].y});
        for (std::size_t i = a; i <= c; ++i) piece.push_back(chain[i]);
        if (last) {
            piece.push_back({b.x1, chain[c].y});
            piece.push_back({b.x1, b.y1});
        } else {
            piece.push_back({chain[c].x, b.y1});
        }
        piece.push_back(first ? PointNm{b.x0, b.y1} : PointNm{chain[a].x, b.y1});
        out.push_back(simplified(std::move(piece)));
        a = c;
    }
}

void lower_pieces(const BoxNm& b, const Ring& hole, std::size_t max_vertices,
                  std::vector<Ring>& out) {
    // Reflect y -> -y (reversing to keep counter-clockwise), take the upper part, reflect back.
    Ring flipped(hole.rbegin(), hole.rend());
    for (PointNm& p : flipped) p.y = -p.y;
    std::vector<Ring> parts;
    upper_pieces({b.x0, -b.y1, b.x1, -b.y0}, flipped, max_vertices, parts);
    for (Ring& part : parts) {
        Ring back(part.rbegin(), part.rend());
        for (PointNm& p : back) p.y = -p.y;
        out.push_back(std::move(back));
    }
}

// Vertical extent of the hole's edge at x == x_extreme, as (lowest y, highest y).
std::pair<std::int64_t, std::int64_t> side_span(const Ring& hole, std::int64_t x_extreme) {
    std::int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (const PointNm& p : hole)
        if (p.x == x_extreme) {
            lo = std::min(lo, p.y);
            hi = std::max(hi, p.y);
        }
    return {lo, hi};
}

}  // namespace

std::vector<Ring> box_minus_convex(const BoxNm& box, const Ring& hole, std::size_t max_vertices) {
    if (max_vertices < 8)
        throw invalid_field("max_vertices", std::to_string(max_vertices), "must be >= 8");
    const BoxNm hb = bounding_box({hole});
    if (!is_strictly_convex_ccw(hole) || hb.x0 <= box.x0 || hb.x1 >= box.x1 || hb.y0 <= box.y0 ||
        hb.y1 >= box.y1)
        throw InvalidInput("box_minus_convex: the hole must be strictly convex and inside the box");
    std::vector<Ring> out;
    upper_pieces(box, hole, max_vertices, out);
    lower_pieces(box, hole, max_vertices, out);
    const auto [llo, lhi] = side_span(hole, hb.x0);
    if (lhi > llo) out.push_back(box_ring({box.x0, llo, hb.x0, lhi}));
    const auto [rlo, rhi] = side_span(hole, hb.x1);
    if (rhi > rlo) out.push_back(box_ring({hb.x1, rlo, box.x1, rhi}));
    return out;
}

std::vector<Ring> dark_pieces(const BoxNm& outline, const std::vector<BoxNm>& holes,
                              const std::vector<ConvexHole>& convex_holes,
                              std::size_t max_vertices) {
    if (max_vertices < 8)
        throw invalid_field("max_vertices", std::to_string(max_vertices), "must be >= 8");
    // Memory budget (core/limits/resource_limits): a 100k-pinhole dark-tone export peaked 540 MB
    // above the clear tone (pieces, their design-rule check, the writers), 5.4 KB a hole: 8 KiB
    // charged.
    check_memory(8192.0 * double(holes.size() + convex_holes.size()), "the dark-tone layout");
    // Every removed rectangle, clipped to the outline.
    std::vector<BoxNm> cut;
    cut.reserve(holes.size() + convex_holes.size());
    auto add = [&](BoxNm b) {
        b = {std::max(b.x0, outline.x0), std::max(b.y0, outline.y0), std::min(b.x1, outline.x1),
             std::min(b.y1, outline.y1)};
        if (b.x0 < b.x1 && b.y0 < b.y1) cut.push_back(b);
    };
    for (const BoxNm& b : holes) add(b);
    for (const ConvexHole& h : convex_holes) add(h.cell);
    std::vector<std::int64_t> levels{outline.y0, outline.y1};
    for (const BoxNm& b : cut) {
        levels.push_back(b.y0);
        levels.push_back(b.y1);
    }
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    std::sort(cut.begin(), cut.end(), [](const BoxNm& a, const BoxNm& b) {
        return a.y0 != b.y0 ? a.y0 < b.y0 : a.x0 < b.x0;
    });

    std::vector<Ring> out;
    std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> open;  // run -> start y
    std::vector<const BoxNm*> active;
    std::vector<std::pair<std::int64_t, std::int64_t>> spans;
    std::size_t next = 0;
    for (std::size_t k = 0; k + 1 < levels.size(); ++k) {  // band [levels[k], levels[k + 1]]
        const std::int64_t ya = levels[k];
        std::erase_if(active, [ya](const BoxNm* b) { return b->y1 <= ya; });
        while (next < cut.size() && cut[next].y0 <= ya) active.push_back(&cut[next++]);
        spans.clear();
        for (const BoxNm* b : active) spans.push_back({b->x0, b->x1});
        std::sort(spans.begin(), spans.end());
        std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> now;
        std::int64_t x = outline.x0;
        auto run = [&](std::int64_t xa, std::int64_t xb) {
            if (xa >= xb) return;
            const auto it = open.find({xa, xb});
            now[{xa, xb}] = it == open.end() ? ya : it->second;
        };
        for (const auto& [s0, s1] : spans) {
            run(x, s0);
            x = std::max(x, s1);
        }
        run(x, outline.x1);
        for (const auto& [span, y0] : open)
            if (!now.count(span)) out.push_back(box_ring({span.first, y0, span.second, ya}));
        open.swap(now);
    }
    for (const auto& [span, y0] : open)
        out.push_back(box_ring({span.first, y0, span.second, levels.back()}));
    for (const ConvexHole& h : convex_holes) {
        std::vector<Ring> parts = box_minus_convex(h.cell, h.polygon, max_vertices);
        for (Ring& p : parts) out.push_back(std::move(p));
    }
    return out;
}

}  // namespace pinmask
