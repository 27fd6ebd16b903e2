#include "design/pattern/mask.hpp"

#include <cmath>
#include <cstdio>

namespace pinmask {
namespace {

void fnv1a(std::uint64_t& h, const std::string& s) {
    for (unsigned char ch : s) {
        h ^= ch;
        h *= 1099511628211ULL;
    }
}

}  // namespace

std::string geometry_hash(const Mask& mask) {
    const Pattern& p = mask.pattern;
    std::uint64_t h = 14695981039346656037ULL;
    char buf[128];
    std::snprintf(buf, sizeof buf, "n=%d;tiles=%dx%d;pinhole_nm=%lld;spacing=%.9g;", p.n,
                  p.tiles_rows, p.tiles_cols, std::llround(mask.camera.pinhole_m * 1e9),
                  p.min_spacing_cells);
    fnv1a(h, buf);
    for (const Cell& c : sorted_pinholes(p)) {
        std::snprintf(buf, sizeof buf, "%d,%d;", c.row, c.col);
        fnv1a(h, buf);
    }
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

}  // namespace pinmask
