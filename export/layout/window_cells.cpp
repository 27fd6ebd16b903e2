#include "export/layout/window_cells.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <tuple>
#include <utility>

namespace pinmask {
namespace {

// Window sizes tried, in lattice pitches (w, h); the first smallest wins.
constexpr std::pair<int, int> kCandidates[] = {{2, 1}, {4, 1}, {8, 1}, {16, 1}, {2, 2}, {4, 2},
                                               {6, 2}, {3, 3}, {4, 3}, {6, 3},  {9, 3}, {12, 3},
                                               {4, 4}, {8, 4}, {6, 6}, {12, 6}};

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    return a / b - ((a % b != 0) && ((a < 0) != (b < 0)));
}

struct Item {
    std::int64_t wx, wy;  // window index
    Placement rel;        // shape and offset from the window corner
};

WindowCells windows_of(const std::vector<Placement>& ps, std::int64_t ox, std::int64_t oy,
                       std::int64_t px, std::int64_t py, int w, int h, const WindowCost& cost) {
    WindowCells out;
    out.w = w;
    out.h = h;
    out.pitch_x_nm = px;
    out.pitch_y_nm = py;
    const std::int64_t sx = px * w, sy = py * h;
    std::vector<Item> items;
    items.reserve(ps.size());
    for (const Placement& p : ps) {
        const std::int64_t wx = floor_div(p.at.x - ox, sx), wy = floor_div(p.at.y - oy, sy);
        items.push_back({wx, wy, {p.shape, {p.at.x - ox - wx * sx, p.at.y - oy - wy * sy}}});
    }
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
        return std::tie(a.wy, a.wx, a.rel.shape, a.rel.at.x, a.rel.at.y) <
               std::tie(b.wy, b.wx, b.rel.shape, b.rel.at.x, b.rel.at.y);
    });
    std::map<std::vector<std::int64_t>, std::size_t> index;
    std::vector<std::int64_t> key;
    std::vector<Placement> content;
    for (std::size_t i = 0; i < items.size();) {
        std::size_t j = i;
        key.clear();
        content.clear();
        while (j < items.size() && items[j].wx == items[i].wx && items[j].wy == items[i].wy) {
            const Placement& r = items[j].rel;
            key.insert(key.end(), {std::int64_t(r.shape), r.at.x, r.at.y});
            content.push_back(r);
            ++j;
        }
        const auto [it, added] = index.try_emplace(key, out.cells.size());
        if (added) out.cells.push_back(content);
        out.uses.push_back({it->second, {ox + items[i].wx * sx, oy + items[i].wy * sy}});
        i = j;
    }
    out.bytes = out.uses.size() * cost.ref_bytes;
    for (const auto& c : out.cells) out.bytes += cost.cell_bytes + c.size() * cost.ref_bytes;
    return out;
}

}  // namespace

WindowCells find_window_cells(const std::vector<Placement>& ps, const WindowCost& cost) {
    WindowCells none;
    none.bytes = ps.size() * cost.ref_bytes;
    if (ps.size() < 2) return none;
    std::int64_t ox = ps[0].at.x, oy = ps[0].at.y;
    for (const Placement& p : ps) ox = std::min(ox, p.at.x), oy = std::min(oy, p.at.y);
    std::int64_t px = 0, py = 0;
    for (const Placement& p : ps) px = std::gcd(px, p.at.x - ox), py = std::gcd(py, p.at.y - oy);
    if (px == 0) px = 1;  // all in one column (or row): any pitch windows them
    if (py == 0) py = 1;
    // Window extents must stay far inside 64 bits (coordinates are 32-bit in GDSII anyway).
    constexpr std::int64_t kMaxPitch = std::int64_t{1} << 32;
    if (px > kMaxPitch || py > kMaxPitch) return none;
    WindowCells best = none;
    for (const auto& [w, h] : kCandidates) {
        WindowCells c = windows_of(ps, ox, oy, px, py, w, h, cost);
        if (c.bytes < best.bytes) best = std::move(c);
    }
    return best;
}

std::vector<Placement> expand_windows(const WindowCells& wc) {
    std::vector<Placement> out;
    for (const Placement& u : wc.uses)
        for (const Placement& r : wc.cells[u.shape])
            out.push_back({r.shape, {u.at.x + r.at.x, u.at.y + r.at.y}});
    return out;
}

}  // namespace pinmask
