#include "export/layout/repetition.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace pinmask {
namespace {

bool placement_less(const Placement& a, const Placement& b) {
    return std::tie(a.shape, a.at.x, a.at.y) < std::tie(b.shape, b.at.x, b.at.y);
}

bool placement_equal(const Placement& a, const Placement& b) {
    return a.shape == b.shape && a.at == b.at;
}

}  // namespace

Repetition find_repetition(const std::vector<Ring>& polygons, const BoxNm& a, int tiles_rows,
                           int tiles_cols) {
    Repetition r;
    std::map<std::vector<std::int64_t>, std::size_t> index;  // shape key -> shape
    std::vector<Placement> all;
    all.reserve(polygons.size());
    for (const Ring& ring : polygons) {
        if (ring.empty()) continue;
        const PointNm o = ring.front();
        std::vector<std::int64_t> key;
        key.reserve(2 * ring.size());
        Ring shape;
        shape.reserve(ring.size());
        for (const PointNm& p : ring) {
            key.push_back(p.x - o.x);
            key.push_back(p.y - o.y);
            shape.push_back({p.x - o.x, p.y - o.y});
        }
        const auto [it, added] = index.try_emplace(std::move(key), r.shapes.size());
        if (added) r.shapes.push_back(std::move(shape));
        all.push_back({it->second, o});
    }
    r.placements = all;
    const std::int64_t w = a.x1 - a.x0, h = a.y1 - a.y0;
    if (tiles_rows * tiles_cols <= 1 || tiles_rows < 1 || tiles_cols < 1 || w % tiles_cols ||
        h % tiles_rows || all.size() % std::size_t(tiles_rows * tiles_cols))
        return r;
    const std::int64_t px = w / tiles_cols, py = h / tiles_rows;
    // Bottom-left tile: polygons whose vertices all lie in [x0, x0 + px] x [y0, y0 + py].
    std::vector<Placement> tile;
    for (std::size_t k = 0, i = 0; k < polygons.size(); ++k) {
        if (polygons[k].empty()) continue;
        bool inside = true;
        for (const PointNm& p : polygons[k])
            inside = inside && p.x >= a.x0 && p.x <= a.x0 + px && p.y >= a.y0 && p.y <= a.y0 + py;
        if (inside) tile.push_back(all[i]);
        ++i;
    }
    if (tile.size() * std::size_t(tiles_rows * tiles_cols) != all.size()) return r;
    Repetition t = r;
    t.placements = tile;
    t.cols = tiles_cols;
    t.rows = tiles_rows;
    t.pitch_x_nm = px;
    t.pitch_y_nm = py;
    std::vector<Placement> want;
    want.reserve(all.size());
    for (int j = 0; j < t.rows; ++j)
        for (int i = 0; i < t.cols; ++i)
            for (const Placement& p : tile)
                want.push_back({p.shape, {p.at.x + i * px, p.at.y + j * py}});
    std::sort(want.begin(), want.end(), placement_less);
    std::sort(all.begin(), all.end(), placement_less);
    if (!std::equal(want.begin(), want.end(), all.begin(), all.end(), placement_equal)) return r;
    return t;
}

std::vector<Ring> expand(const Repetition& r) {
    std::vector<Ring> out;
    out.reserve(r.polygon_count());
    for (int j = 0; j < r.rows; ++j)
        for (int i = 0; i < r.cols; ++i)
            for (const Placement& p : r.placements) {
                Ring ring = r.shapes[p.shape];
                const std::int64_t dx = p.at.x + i * r.pitch_x_nm, dy = p.at.y + j * r.pitch_y_nm;
                for (PointNm& v : ring) v = {v.x + dx, v.y + dy};
                out.push_back(std::move(ring));
            }
    return out;
}

}  // namespace pinmask
