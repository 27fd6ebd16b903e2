#include "report/report_pages.hpp"

#include <algorithm>
#include <string>

#include "report/report_draw.hpp"

namespace pinmask::report_pages {
namespace {

using report_draw::Box;
using report_draw::Font;

// Page frame (points).
constexpr double kMargin = 32.0;
constexpr double kFooterHeight = 16.0;  // page number line at the bottom, see report.cpp
constexpr double kContentWidth = kReportPageWidthPt - 2 * kMargin;
constexpr double kBottom = kReportPageHeightPt - kMargin - kFooterHeight;

// Text blocks: font, then the distance from one baseline to the next.
const Font kTitleFont{16.0, true, false};
constexpr double kTitleAdvance = 24.0;
const Font kMaskTitleFont{14.0, true, false};
constexpr double kMaskTitleAdvance = 20.0;
const Font kLineFont{9.0, false, false};
constexpr double kLineAdvance = 12.0;
constexpr double kBlockGap = 10.0;

// Table: natural font size, the smallest it may shrink to so a wide table fits the page, cell
// padding, row height per point of font size, a floor for a truncated first column.
constexpr double kTableFontPt = 8.5;
constexpr double kTableMinFontPt = 5.5;
constexpr double kCellPadPt = 4.0;
constexpr double kRowPerFontPt = 1.6;
constexpr double kMinFirstColumnPt = 60.0;
constexpr double kStripeGrey = 0.94;

// Panel grid.
constexpr int kMaxGridColumns = 4;
constexpr double kGridHGap = 14.0, kGridVGap = 10.0;
const Font kCaptionFont{9.0, true, false};
const Font kSmallFont{7.5, false, false};
const Font kNoteFont{8.5, false, false};
constexpr double kCaptionAdvance = 12.0;
constexpr double kBarGap = 3.0, kBarHeight = 7.0, kBarLabelAdvance = 10.0;
constexpr double kScaleAdvance = 10.0, kNoteAdvance = 11.0;

struct TableLayout {
    double font = kTableFontPt;
    std::vector<double> widths;
    double row_height() const { return font * kRowPerFontPt; }
    bool has_units = false;
    double header_height() const { return row_height() * (has_units ? 2.0 : 1.0) + 2.0; }
};

Font cell_font(double size, bool bold = false) { return {size, bold, false}; }

TableLayout table_layout(cairo_t* cr, const ReportTable& t) {
    TableLayout L;
    L.has_units = false;
    for (const auto& u : t.units) L.has_units = L.has_units || !u.empty();
    auto measure = [&](double size) {
        L.font = size;
        L.widths.assign(t.headers.size(), 0.0);
        for (std::size_t c = 0; c < t.headers.size(); ++c) {
            double w = report_draw::text_width(cr, t.headers[c], cell_font(size, true));
            if (c < t.units.size())
                w = std::max(w, report_draw::text_width(cr, t.units[c], cell_font(0.85 * size)));
            for (const auto& row : t.rows)
                w = std::max(w, report_draw::text_width(cr, row[c], cell_font(size)));
            L.widths[c] = w + 2 * kCellPadPt;
        }
        double total = 0.0;
        for (double w : L.widths) total += w;
        return total;
    };
    const double total = measure(kTableFontPt);
    if (total > kContentWidth) {
        const double shrunk = std::max(kTableMinFontPt, kTableFontPt * kContentWidth / total);
        const double total2 = measure(shrunk);
        if (total2 > kContentWidth) {  // still too wide: the first column gives way
            L.widths[0] = std::max(kMinFirstColumnPt, L.widths[0] - (total2 - kContentWidth));
        }
    }
    return L;
}

std::vector<std::string> wrap_all(cairo_t* cr, const std::vector<std::string>& lines,
                                  const Font& font) {
    std::vector<std::string> out;
    for (const auto& l : lines) {
        for (auto& w : report_draw::wrap_text(cr, l, font, kContentWidth)) out.push_back(w);
    }
    return out;
}

void draw_table_rows(cairo_t* cr, const ReportTable& t, const TableLayout& L, std::size_t begin,
                     std::size_t end, double y) {
    const double rh = L.row_height();
    double total = 0.0;
    for (double w : L.widths) total += w;
    // Header: names (bold), units (italic, smaller), a rule.
    double x = kMargin;
    for (std::size_t c = 0; c < t.headers.size(); ++c) {
        const double w = L.widths[c];
        const double ax = c == 0 ? x + kCellPadPt : x + w - kCellPadPt;
        const double align = c == 0 ? 0.0 : 1.0;
        const Font hf = cell_font(L.font, true);
        report_draw::draw_text(cr, ax, y + rh * 0.72,
                               report_draw::fit_text(cr, t.headers[c], hf, w - 2 * kCellPadPt), hf,
                               align);
        if (L.has_units && c < t.units.size()) {
            const Font uf{0.85 * L.font, false, true};
            report_draw::draw_text(cr, ax, y + rh * 1.62,
                                   report_draw::fit_text(cr, t.units[c], uf, w - 2 * kCellPadPt),
                                   uf, align);
        }
        x += w;
    }
    y += L.header_height();
    cairo_set_line_width(cr, 0.8);
    cairo_move_to(cr, kMargin, y);
    cairo_line_to(cr, kMargin + total, y);
    cairo_stroke(cr);
    for (std::size_t r = begin; r < end; ++r) {
        if ((r - begin) % 2 == 1) {
            cairo_save(cr);
            cairo_set_source_rgb(cr, kStripeGrey, kStripeGrey, kStripeGrey);
            cairo_rectangle(cr, kMargin, y, total, rh);
            cairo_fill(cr);
            cairo_restore(cr);
        }
        x = kMargin;
        for (std::size_t c = 0; c < t.headers.size(); ++c) {
            const double w = L.widths[c];
            const Font f = cell_font(L.font);
            const std::string s = report_draw::fit_text(cr, t.rows[r][c], f, w - 2 * kCellPadPt);
            report_draw::draw_text(cr, c == 0 ? x + kCellPadPt : x + w - kCellPadPt, y + rh * 0.7,
                                   s, f, c == 0 ? 0.0 : 1.0);
            x += w;
        }
        y += rh;
    }
    cairo_set_line_width(cr, 0.8);
    cairo_move_to(cr, kMargin, y);
    cairo_line_to(cr, kMargin + total, y);
    cairo_stroke(cr);
}

}  // namespace

std::vector<TablePage> plan_table_pages(const ReportDocument& doc) {
    report_draw::Measure m;
    const TableLayout L = table_layout(m.cr(), doc.table);
    const std::size_t summary = wrap_all(m.cr(), doc.lines, kLineFont).size();
    const std::size_t notes = wrap_all(m.cr(), doc.notes, kLineFont).size();
    const std::size_t rows = doc.table.rows.size();
    std::vector<TablePage> pages;
    std::size_t r = 0, n = 0;
    bool table_done = false;
    for (bool first = true;; first = false) {
        TablePage p;
        p.first = first;
        double y = kMargin + kTitleAdvance;
        if (first) y += static_cast<double>(summary) * kLineAdvance + kBlockGap;
        if (!table_done) {
            // The header goes with at least one row (or alone when there are none); a fresh
            // page always takes it, so the loop progresses.
            const double need = L.header_height() + (r < rows ? L.row_height() : 0.0);
            if (y + need <= kBottom || !first) {
                p.has_table = true;
                p.row_begin = r;
                y += L.header_height();
                do {
                    if (r < rows) ++r;
                    y += L.row_height();
                } while (r < rows && y + L.row_height() <= kBottom);
                p.row_end = r;
                y += kBlockGap;
                table_done = r == rows;
            }
        }
        if (table_done) {
            p.note_begin = n;
            while (n < notes && y + kLineAdvance <= kBottom) {
                ++n;
                y += kLineAdvance;
            }
            if (!first && !p.has_table && n == p.note_begin && n < notes) ++n;  // progress
            p.note_end = n;
        }
        pages.push_back(p);
        if (table_done && n == notes) break;
    }
    return pages;
}

void draw_table_page(cairo_t* cr, const ReportDocument& doc, const TablePage& page) {
    report_draw::prepare_context(cr);
    const TableLayout L = table_layout(cr, doc.table);
    double y = kMargin;
    report_draw::draw_text(
        cr, kMargin, y + kTitleFont.size,
        report_draw::fit_text(cr, page.first ? doc.title : doc.title + " (cont.)", kTitleFont,
                              kContentWidth),
        kTitleFont);
    y += kTitleAdvance;
    if (page.first) {
        for (const auto& l : wrap_all(cr, doc.lines, kLineFont)) {
            report_draw::draw_text(cr, kMargin, y + kLineFont.size, l, kLineFont);
            y += kLineAdvance;
        }
        y += kBlockGap;
    }
    if (page.has_table) {
        draw_table_rows(cr, doc.table, L, page.row_begin, page.row_end, y);
        y +=
            L.header_height() + L.row_height() * static_cast<double>(page.row_end - page.row_begin);
        if (page.row_end == page.row_begin) y += L.row_height();  // the planner's empty row
        y += kBlockGap;
    }
    const std::vector<std::string> notes = wrap_all(cr, doc.notes, kLineFont);
    for (std::size_t i = page.note_begin; i < page.note_end; ++i) {
        report_draw::draw_text(cr, kMargin, y + kLineFont.size, notes[i], kLineFont);
        y += kLineAdvance;
    }
}

void draw_mask_page(cairo_t* cr, const ReportMaskPage& page) {
    report_draw::prepare_context(cr);
    double y = kMargin;
    report_draw::draw_text(cr, kMargin, y + kMaskTitleFont.size,
                           report_draw::fit_text(cr, page.title, kMaskTitleFont, kContentWidth),
                           kMaskTitleFont);
    y += kMaskTitleAdvance;
    for (const auto& l : wrap_all(cr, page.lines, kLineFont)) {
        report_draw::draw_text(cr, kMargin, y + kLineFont.size, l, kLineFont);
        y += kLineAdvance;
    }
    y += kBlockGap / 2;

    const int count = static_cast<int>(page.panels.size());
    const int cols = std::min(kMaxGridColumns, count);
    const int grid_rows = (count + cols - 1) / cols;
    const double cell_w = (kContentWidth - (cols - 1) * kGridHGap) / cols;
    const double cell_h = (kBottom - y - (grid_rows - 1) * kGridVGap) / grid_rows;
    for (int gr = 0; gr < grid_rows; ++gr) {
        // Rows share one layout so images and colour bars line up across the row.
        std::size_t notes = 0;
        bool bar = false;
        for (int gc = 0; gc < cols && gr * cols + gc < count; ++gc) {
            const ReportPanel& p = page.panels[static_cast<std::size_t>(gr * cols + gc)];
            notes = std::max(notes, p.notes.size());
            bar = bar || p.colorbar;
        }
        const double below = (bar ? kBarGap + kBarHeight + kBarLabelAdvance : 0.0) + kScaleAdvance +
                             static_cast<double>(notes) * kNoteAdvance + 2.0;
        const double top = y + gr * (cell_h + kGridVGap);
        const double image_h = std::max(10.0, cell_h - kCaptionAdvance - below);
        for (int gc = 0; gc < cols && gr * cols + gc < count; ++gc) {
            const ReportPanel& p = page.panels[static_cast<std::size_t>(gr * cols + gc)];
            const double x = kMargin + gc * (cell_w + kGridHGap);
            report_draw::draw_text(cr, x, top + kCaptionFont.size,
                                   report_draw::fit_text(cr, p.caption, kCaptionFont, cell_w),
                                   kCaptionFont);
            const Box img = report_draw::draw_plane(cr, p.values, p.lo, p.hi,
                                                    {x, top + kCaptionAdvance, cell_w, image_h});
            double yb = top + kCaptionAdvance + image_h;
            if (bar) {
                if (p.colorbar) {
                    report_draw::draw_colorbar(cr, {img.x, yb + kBarGap, img.w, kBarHeight}, p.lo,
                                               p.hi, p.unit, kSmallFont);
                }
                yb += kBarGap + kBarHeight + kBarLabelAdvance;
            }
            report_draw::draw_text(cr, x, yb + kSmallFont.size + 1.0,
                                   report_draw::fit_text(cr, p.scale, kSmallFont, cell_w),
                                   kSmallFont);
            yb += kScaleAdvance;
            for (const auto& note : p.notes) {
                report_draw::draw_text(cr, x, yb + kNoteFont.size + 1.0,
                                       report_draw::fit_text(cr, note, kNoteFont, cell_w),
                                       kNoteFont);
                yb += kNoteAdvance;
            }
        }
    }
}

}  // namespace pinmask::report_pages
