#include "export/layout/geometry.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "design/optics/fab_grid.hpp"
#include "export/layout/cell_union.hpp"
#include "export/layout/dark_tone.hpp"
#include "export/layout/marks.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/shapes.hpp"
#include "export/layout/xor_area.hpp"

namespace pinmask {
namespace {

std::int64_t length_nm(double metres, std::int64_t grid, const char* field, bool allow_zero) {
    const double nm = metres * 1e9;
    if (!std::isfinite(nm) || nm < 0 || (!allow_zero && nm == 0))
        throw invalid_field(field, nm_text(nm), allow_zero ? "must be >= 0" : "must be > 0");
    if (nm > double(kMaxCoordNm)) throw invalid_field(field, nm_text(nm), "is larger than 2^30 nm");
    return snap_nm(nm, grid);
}

// Tiled pinhole cells (row, col of the tiled mask) in row-major order.
std::vector<Cell> tiled_cells(const Pattern& p) {
    std::vector<std::vector<int>> by_row(std::size_t(p.n));
    for (const Cell& c : sorted_pinholes(p)) by_row[std::size_t(c.row)].push_back(c.col);
    std::vector<Cell> out;
    out.reserve(p.pinholes.size() * std::size_t(p.tiles_rows) * std::size_t(p.tiles_cols));
    for (int tr = 0; tr < p.tiles_rows; ++tr)
        for (int r = 0; r < p.n; ++r)
            for (int tc = 0; tc < p.tiles_cols; ++tc)
                for (int c : by_row[std::size_t(r)]) out.push_back({tr * p.n + r, tc * p.n + c});
    return out;
}

// True when two pinholes of the tiled mask share a cell edge (full-cell squares then touch).
bool edge_neighbours(const Pattern& p) {
    const std::vector<std::uint8_t> occ = occupancy(p);
    const int n = p.n;
    for (const Cell& c : p.pinholes) {
        const bool wrap_c = p.tiles_cols > 1, wrap_r = p.tiles_rows > 1;
        if ((c.col + 1 < n || wrap_c) && occ[std::size_t(c.row) * n + (c.col + 1) % n]) return true;
        if ((c.row + 1 < n || wrap_r) && occ[std::size_t((c.row + 1) % n) * n + c.col]) return true;
    }
    return false;
}

}  // namespace

HoleShape parse_hole_shape(std::string_view text, std::string_view field) {
    if (text == "square") return HoleShape::kSquare;
    if (text == "circle") return HoleShape::kCircle;
    if (text == "polygon") return HoleShape::kPolygon;
    throw invalid_field(std::string(field), std::string(text), "must be square, circle or polygon");
}

Tone parse_tone(std::string_view text, std::string_view field) {
    if (text == "clear" || text == "negative") return Tone::kClear;
    if (text == "dark" || text == "positive") return Tone::kDark;
    throw invalid_field(std::string(field), std::string(text),
                        "must be clear (alias negative: the drawn polygons are the clear "
                        "pinholes) or dark (alias positive: the drawn polygons are the opaque "
                        "film)");
}

std::string tone_words(Tone tone) {
    return tone == Tone::kClear ? "clear (negative): polygons are the clear pinholes"
                                : "dark (positive): polygons are the opaque film";
}

std::string tone_label_line(Tone tone, bool mirrored, std::string_view unit) {
    return label_text(std::string(tone == Tone::kClear ? "CLEAR HOLES NEG" : "DARK FILM POS") +
                      (mirrored ? " EMUL DOWN" : " EMUL UP") + " UNIT " + std::string(unit));
}

std::string tone_name(Tone tone) { return tone == Tone::kClear ? "clear" : "dark"; }

std::vector<std::string> default_label_lines(const Mask& mask, std::string_view id) {
    char pitch[64];
    std::snprintf(pitch, sizeof pitch, "SCALE 1:1 D %.6gUM", mask.camera.pinhole_m * 1e6);
    return {label_text("ID " + std::string(id)), label_text("H " + geometry_hash(mask)),
            label_text(pitch)};
}

std::string layout_info(const Layout& layout, std::string_view units) {
    return "hash=" + layout.mask_hash + " tone=" + tone_name(layout.tone) +
           " drawn=" + (layout.tone == Tone::kClear ? "clear" : "opaque") +
           " mirrored=" + (layout.mirrored ? "yes" : "no") + " units=" + std::string(units) +
           " grid_nm=" + std::to_string(layout.grid_nm);
}

std::map<std::string, std::string> parse_info(std::string_view text) {
    std::map<std::string, std::string> out;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        const std::size_t start = i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        const std::string_view word = text.substr(start, i - start);
        const std::size_t eq = word.find('=');
        if (eq != std::string_view::npos && eq > 0)
            out[std::string(word.substr(0, eq))] = std::string(word.substr(eq + 1));
    }
    return out;
}

std::vector<Ring> all_rings(const Layout& layout) {
    std::vector<Ring> out = layout.polygons;
    out.insert(out.end(), layout.annotations.begin(), layout.annotations.end());
    return out;
}

Layout make_layout(const Mask& mask, const LayoutOptions& o) {
    const Pattern& p = mask.pattern;
    validate(p, /*allow_spacing_violations=*/true);  // touching shapes are merged below
    validate(mask.camera);
    if (p.pinholes.empty())
        throw invalid_field("pattern.pinholes", "0 pinholes",
                            "the export would be empty: a mask needs at least one pinhole");
    const double grid_exact = o.grid_m * 1e9;
    const std::int64_t grid = std::llround(grid_exact);
    if (!std::isfinite(grid_exact) || grid < 1 || std::fabs(grid_exact - double(grid)) > 1e-6)
        throw invalid_field("grid", nm_text(grid_exact), "must be a whole number of nm >= 1");
    if (!(o.chord_tolerance_m >= 0) || !std::isfinite(o.chord_tolerance_m))
        throw invalid_field("chord_tolerance", nm_text(o.chord_tolerance_m * 1e9),
                            "must be finite and >= 0 (0: auto)");
    if (o.max_vertices < 8)
        throw invalid_field("max_vertices", std::to_string(o.max_vertices), "must be >= 8");

    // The cell pitch on the grid (design/optics/fab_grid): every cell edge is a whole number of
    // pitches from the first, so pinholes k cells apart are exactly sqrt(k) P apart.
    const double pitch_design = mask.camera.pinhole_m * 1e9;
    if (pitch_design < 8.0 * double(grid))
        throw invalid_field("pinhole_m", nm_text(pitch_design), "must be at least 8 grid steps");
    const std::int64_t pitch_nm = pitch_on_grid_nm(mask.camera.pinhole_m, grid);
    const double pitch = double(pitch_nm);
    // A hole side given as the design's own d (e.g. an export sidecar's) is the whole cell.
    double hole = o.hole_side_m > 0 ? o.hole_side_m * 1e9 : pitch;
    if (o.hole_side_m > 0 && std::fabs(hole - pitch_design) <= 0.5 * double(grid)) hole = pitch;
    if (!std::isfinite(hole) || o.hole_side_m < 0 || hole > pitch * (1 + 1e-12))
        throw invalid_field("hole_side", nm_text(hole),
                            "must be > 0 and <= the cell pitch " + nm_text(pitch));
    // Snapping both edges to the grid can move each by up to one step: below two steps a square
    // pinhole could collapse to zero area (and the files would carry empty rings).
    if (hole < 2.0 * double(grid))
        throw invalid_field("hole_side", nm_text(hole),
                            "must be at least 2 grid steps (" + nm_text(2.0 * double(grid)) +
                                ") so that no pinhole vanishes on the grid");
    const bool full_cell = hole >= pitch * (1 - 1e-12);
    if (!full_cell && pitch - hole < 2.0 * double(grid))
        throw invalid_field("hole_side", nm_text(hole),
                            "must equal the cell pitch or be at least 2 grid steps smaller");
    const std::int64_t rows = std::int64_t(p.n) * p.tiles_rows;
    const std::int64_t cols = std::int64_t(p.n) * p.tiles_cols;
    const std::int64_t frame = length_nm(o.frame_m, grid, "frame", true);
    const double half_w = 0.5 * double(cols) * pitch, half_h = 0.5 * double(rows) * pitch;
    // The active area's left and bottom edges: half the tiled size, rounded down to the grid, so
    // the centre is the origin within one grid step.
    const std::int64_t left = -floor_to_grid(half_w, grid), bottom = -floor_to_grid(half_h, grid);
    if (std::max(half_w, half_h) + double(frame) > 0.5 * double(kMaxCoordNm))
        throw invalid_field("mask size", nm_text(2 * std::max(half_w, half_h)),
                            "the outline must fit in +-2^29 nm (about 0.54 m) per side");
    const std::size_t count = p.pinholes.size() * std::size_t(p.tiles_rows * p.tiles_cols);

    int sides = 4;
    std::vector<std::pair<double, double>> offsets;
    if (o.shape != HoleShape::kSquare) {
        // Clear tone: each circle is one polygon, so it must fit max_vertices. Dark tone: the
        // circles are holes in pieces that are split to max_vertices anyway, so an explicit
        // tolerance may need more sides (auto stays within max_vertices in both tones).
        const bool one_polygon = o.tone == Tone::kClear || o.chord_tolerance_m == 0.0;
        const std::size_t limit =
            one_polygon ? o.max_vertices : static_cast<std::size_t>(kMaxPolygonSides);
        sides = o.shape == HoleShape::kCircle
                    ? circle_sides(hole / 2, o.chord_tolerance_m * 1e9, limit, grid)
                    : o.polygon_sides;
        if (sides < 3 || sides > kMaxPolygonSides)
            throw invalid_field("sides", std::to_string(sides),
                                "must be in 3.." + std::to_string(kMaxPolygonSides));
        offsets = regular_polygon_offsets(hole / 2, sides);
    }
    check_memory(double(count) * (16.0 * sides + 64.0) * 2.0, "export layout polygons");

    std::vector<std::int64_t> xe(std::size_t(cols) + 1), ye(std::size_t(rows) + 1);
    for (std::int64_t j = 0; j <= cols; ++j) xe[j] = left + j * pitch_nm;
    for (std::int64_t i = 0; i <= rows; ++i) ye[i] = bottom + (rows - i) * pitch_nm;

    Layout layout;
    layout.grid_nm = grid;
    layout.pitch_nm = pitch_nm;
    layout.tone = o.tone;
    layout.mirrored = o.mirror;
    layout.mask_hash = geometry_hash(mask);
    layout.hole_sides = sides;
    layout.tiles_rows = p.tiles_rows;
    layout.tiles_cols = p.tiles_cols;
    layout.active_area = {xe.front(), ye.back(), xe.back(), ye.front()};
    const BoxNm& a = layout.active_area;
    const BoxNm outline{a.x0 - frame, a.y0 - frame, a.x1 + frame, a.y1 + frame};

    const std::vector<Cell> cells = tiled_cells(p);
    auto cell_box = [&](const Cell& c) {
        return BoxNm{xe[c.col], ye[c.row + 1], xe[c.col + 1], ye[c.row]};
    };
    // Every pinhole is the one of cell (0, 0) moved by whole pitches, so all pinholes are
    // identical on the grid and their centres exactly whole pitches apart.
    const BoxNm first_cell = cell_box({0, 0});
    const double first_cx = double(first_cell.x0) + 0.5 * pitch;
    const double first_cy = double(first_cell.y0) + 0.5 * pitch;
    auto moved = [&](const Cell& c) {
        return std::pair{std::int64_t(c.col) * pitch_nm, -std::int64_t(c.row) * pitch_nm};
    };
    // The square hole inside its cell: side and inset snapped once.
    const std::int64_t hole_nm = snap_nm(hole, grid);
    const std::int64_t inset = full_cell ? 0 : snap_nm(0.5 * (pitch - double(hole_nm)), grid);
    auto hole_box = [&](const Cell& c) {
        if (full_cell) return cell_box(c);
        const BoxNm cb = cell_box(c);
        return BoxNm{cb.x0 + inset, cb.y0 + inset, cb.x0 + inset + hole_nm,
                     cb.y0 + inset + hole_nm};
    };
    Ring first_polygon;
    if (o.shape != HoleShape::kSquare)
        first_polygon = place_polygon(offsets, first_cx, first_cy, first_cell, grid);
    auto polygon_in = [&](const Cell& c) {
        const auto [dx, dy] = moved(c);
        Ring r = first_polygon;
        for (PointNm& q : r) q = {q.x + dx, q.y + dy};
        return r;
    };

    if (o.tone == Tone::kClear) {
        if (o.shape != HoleShape::kSquare) {
            layout.polygons.reserve(cells.size());
            for (const Cell& c : cells) layout.polygons.push_back(polygon_in(c));
            if (o.shape == HoleShape::kCircle) {
                // The true circles, centre and diameter on the grid (native circle output).
                // (an even number of grid steps, so the radius is on the grid too)
                const std::int64_t diameter = 2 * std::max(grid, snap_nm(hole / 2, grid));
                layout.circles.reserve(cells.size());
                const PointNm first{first_cell.x0 + floor_to_grid(0.5 * pitch, grid),
                                    first_cell.y0 + floor_to_grid(0.5 * pitch, grid)};
                for (const Cell& c : cells) {
                    const auto [dx, dy] = moved(c);
                    layout.circles.push_back({{first.x + dx, first.y + dy}, diameter});
                }
            }
        } else if (full_cell && edge_neighbours(p)) {
            check_memory(double(rows) * double(cols) * 6.0, "merging touching pinholes");
            std::vector<std::uint8_t> occ(std::size_t(rows) * std::size_t(cols), 0);
            for (const Cell& c : cells) occ[std::size_t(c.row) * std::size_t(cols) + c.col] = 1;
            layout.polygons = union_of_cells(occ, int(rows), int(cols), xe, ye, o.max_vertices);
        } else {
            layout.polygons.reserve(cells.size());
            for (const Cell& c : cells) layout.polygons.push_back(box_ring(hole_box(c)));
        }
    } else {
        std::vector<BoxNm> boxes;
        std::vector<ConvexHole> convex;
        for (const Cell& c : cells) {
            if (o.shape == HoleShape::kSquare)
                boxes.push_back(hole_box(c));
            else
                convex.push_back({cell_box(c), polygon_in(c)});
        }
        layout.polygons = dark_pieces(outline, boxes, convex, o.max_vertices);
    }

    if (o.marks) {
        const std::int64_t arm = length_nm(o.mark_arm_m, grid, "mark_arm", false);
        const std::int64_t hw = length_nm(o.mark_width_m / 2, grid, "mark_width", false);
        const std::int64_t gap = length_nm(o.mark_gap_m, grid, "mark_gap", false);
        if (!(arm > hw && hw > 0 && gap > 0))
            throw invalid_field("mark_width", nm_text(2.0 * double(hw)),
                                "must be > 0 and below twice the arm " + nm_text(double(arm)) +
                                    " (after snapping to the grid)");
        layout.annotations = corner_crosses(outline, arm, hw, gap);
    }
    if (!o.label_lines.empty()) {
        const std::int64_t px = length_nm(o.label_pixel_m, grid, "label_pixel", false);
        const std::int64_t gap = length_nm(o.mark_gap_m, grid, "mark_gap", false);
        const std::int64_t bar_gap = std::max(grid, snap_nm(double(px) / 2, grid));
        if (px <= bar_gap || gap <= 0)
            throw invalid_field("label_pixel", nm_text(double(px)), "must be >= 2 grid steps");
        std::int64_t top = outline.y0 - gap;
        if (o.marks)
            top -= 2 * length_nm(o.mark_arm_m, grid, "mark_arm", false) + gap;  // below crosses
        std::vector<Ring> text = text_rings(o.label_lines, {outline.x0, top}, px, bar_gap);
        layout.annotations.insert(layout.annotations.end(), text.begin(), text.end());
    }
    layout.extent = box_union(
        outline, bounding_box(layout.annotations.empty() ? std::vector<Ring>{box_ring(outline)}
                                                         : layout.annotations));
    const BoxNm& e = layout.extent;
    if (std::max({-e.x0, -e.y0, e.x1, e.y1}) > kMaxCoordNm)
        throw invalid_field("extent", nm_text(double(std::max({-e.x0, -e.y0, e.x1, e.y1}))),
                            "marks and label must stay within +-2^30 nm");
    if (o.mirror) {
        for (Ring& r : layout.polygons) r = mirrored_about_y_axis(r);
        for (Ring& r : layout.annotations) r = mirrored_about_y_axis(r);
        for (CircleNm& c : layout.circles) c.centre.x = -c.centre.x;
        auto flip = [](BoxNm& b) { b = {-b.x1, b.y0, -b.x0, b.y1}; };
        flip(layout.active_area);
        flip(layout.extent);
    }
    return layout;
}

}  // namespace pinmask
