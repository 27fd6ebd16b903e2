// Page layouts of the comparison report (report/report.hpp): the table pages (title, summary,
// metrics table continued over as many pages as it needs, notes) and the mask pages (title,
// lines, a grid of panels). Coordinates in points, y down, on a kReportPageWidthPt x
// kReportPageHeightPt page. Layout depends only on the document and font metrics, so every
// output format paginates identically.
#pragma once

#include <cairo.h>

#include <cstddef>
#include <vector>

#include "report/report.hpp"

namespace pinmask::report_pages {

// What one table page holds: the summary (first page only), rows [row_begin, row_end) with the
// header repeated, notes [note_begin, note_end) (notes are already wrapped lines).
struct TablePage {
    bool first = false;
    bool has_table = false;
    std::size_t row_begin = 0, row_end = 0;
    std::size_t note_begin = 0, note_end = 0;
};

// The table pages of the document, at least one.
std::vector<TablePage> plan_table_pages(const ReportDocument& doc);

// Draws table page `page` (of plan_table_pages) onto a blank page.
void draw_table_page(cairo_t* cr, const ReportDocument& doc, const TablePage& page);

// Draws one mask page.
void draw_mask_page(cairo_t* cr, const ReportMaskPage& page);

}  // namespace pinmask::report_pages
