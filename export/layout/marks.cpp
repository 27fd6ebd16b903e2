#include "export/layout/marks.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>

#include "core/errors/error.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {
namespace {

struct Glyph {
    char c;
    std::array<std::uint8_t, 7> rows;  // top to bottom; bit 4 is the leftmost column
};

// The classic 5 x 7 character-display shapes.
constexpr Glyph kFont[] = {
    {' ', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}},
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'A', {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11}},
    {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
    {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
    {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
    {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}},
    {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
    {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}},
    {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}},
    {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
};

const Glyph* find_glyph(char c) {
    for (const Glyph& g : kFont)
        if (g.c == c) return &g;
    return nullptr;
}

constexpr int kAdvanceX = 6;  // pixels per character
constexpr int kAdvanceY = 9;  // pixels per line

}  // namespace

Ring cross_ring(PointNm c, std::int64_t a, std::int64_t h) {
    if (!(a > h && h > 0))
        throw InvalidInput("cross_ring: needs arm > half width > 0 (got arm " + std::to_string(a) +
                           " nm, half width " + std::to_string(h) + " nm)");
    return {{c.x + h, c.y - a}, {c.x + h, c.y - h}, {c.x + a, c.y - h}, {c.x + a, c.y + h},
            {c.x + h, c.y + h}, {c.x + h, c.y + a}, {c.x - h, c.y + a}, {c.x - h, c.y + h},
            {c.x - a, c.y + h}, {c.x - a, c.y - h}, {c.x - h, c.y - h}, {c.x - h, c.y - a}};
}

std::vector<Ring> corner_crosses(const BoxNm& o, std::int64_t arm, std::int64_t hw,
                                 std::int64_t gap) {
    const std::int64_t d = gap + arm;  // centre offset: the arm tips stay `gap` clear
    return {cross_ring({o.x0 - d, o.y0 - d}, arm, hw), cross_ring({o.x1 + d, o.y0 - d}, arm, hw),
            cross_ring({o.x1 + d, o.y1 + d}, arm, hw), cross_ring({o.x0 - d, o.y1 + d}, arm, hw)};
}

bool has_glyph(char c) { return find_glyph(c) != nullptr; }

std::string label_text(std::string_view text) {
    std::string out;
    for (char c : text) {
        const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        out.push_back(has_glyph(u) ? u : '-');
    }
    return out;
}

std::vector<Ring> text_rings(const std::vector<std::string>& lines, PointNm top_left,
                             std::int64_t px, std::int64_t gap) {
    if (!(px > gap && gap > 0))
        throw InvalidInput("text_rings: needs pixel > gap > 0 (got pixel " + std::to_string(px) +
                           " nm, gap " + std::to_string(gap) + " nm)");
    std::vector<Ring> out;
    for (std::size_t li = 0; li < lines.size(); ++li) {
        const std::string& line = lines[li];
        for (std::size_t k = 0; k < line.size(); ++k) {
            const Glyph* g = find_glyph(line[k]);
            if (!g)
                throw invalid_field("label", line,
                                    std::string("character '") + line[k] + "' has no glyph");
            for (int row = 0; row < 7; ++row) {
                const std::int64_t top = top_left.y - (std::int64_t(li) * kAdvanceY + row) * px;
                for (int col = 0; col < 5;) {
                    if (!(g->rows[row] & (0x10 >> col))) {
                        ++col;
                        continue;
                    }
                    int end = col;
                    while (end + 1 < 5 && (g->rows[row] & (0x10 >> (end + 1)))) ++end;
                    const std::int64_t left = top_left.x + (std::int64_t(k) * kAdvanceX + col) * px;
                    const std::int64_t right =
                        top_left.x + (std::int64_t(k) * kAdvanceX + end + 1) * px - gap;
                    out.push_back(box_ring({left, top - px + gap, right, top}));
                    col = end + 1;
                }
            }
        }
    }
    return out;
}

BoxNm text_box(const std::vector<std::string>& lines, PointNm top_left, std::int64_t px) {
    std::size_t longest = 0;
    for (const std::string& l : lines) longest = std::max(longest, l.size());
    const std::int64_t w = longest ? (std::int64_t(longest) * kAdvanceX - 1) * px : 0;
    const std::int64_t h = lines.empty() ? 0 : (std::int64_t(lines.size()) * kAdvanceY - 2) * px;
    return {top_left.x, top_left.y - h, top_left.x + w, top_left.y};
}

}  // namespace pinmask
