// The comparison report (`pinmask compare --report`): a title page with a summary and a metrics
// table, then one page per mask with a grid of grey-scale image panels, drawn with Cairo as one
// multi-page PDF or as one SVG or PNG file per page. The report takes plain data only (strings,
// numbers, core Planes): whoever builds it computes the metrics and images.
//
// Page geometry, once for this file: A4 landscape, kReportPageWidthPt x kReportPageHeightPt
// points (1 pt = 1/72 in); PNG pages are rasterised at `pixels_per_point`. Text uses Cairo's toy
// font API with the fontconfig family "sans-serif". Panels map a value v to grey
// t = (v - lo) / (hi - lo), clipped to [0, 1] (0 black, 1 white); -inf draws black, +inf white.
// Image pixels are drawn as sharp squares (nearest-neighbour), row 0 at the top.
//
// Determinism: the same document gives the same bytes on one build and font set. PDF creation
// and modification dates are pinned (as export/formats/pdf_writer does); Cairo's SVG surface
// numbers images and surfaces with process-wide counters, so those ids are renumbered in order of
// first appearance.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

inline constexpr double kReportPageWidthPt = 841.89;     // A4 landscape, 297 mm
inline constexpr double kReportPageHeightPt = 595.28;    // 210 mm
inline constexpr double kReportPngPixelsPerPoint = 2.0;  // 144 dpi: table text stays legible

// One image in a page's grid.
struct ReportPanel {
    std::string caption;             // above the image
    Plane values;                    // rows x cols >= 1; NaN is refused
    double lo = 0.0, hi = 1.0;       // display range, finite, lo < hi
    bool colorbar = true;            // grey ramp under the image labelled lo .. hi
    std::string unit;                // printed after the colour-bar labels ("" for none)
    std::string scale;               // size / scale line, e.g. "128 x 128 px, 1 px = 30 um"
    std::vector<std::string> notes;  // lines under the image (figures)
};

// One page per mask: a title, a few summary lines and the panels in a grid (up to 4 columns).
struct ReportMaskPage {
    std::string title;
    std::vector<std::string> lines;
    std::vector<ReportPanel> panels;  // at least one
};

// A table of text cells: headers with a unit line each (may be ""), rows of the same width.
// The first column is left-aligned, the others right-aligned.
struct ReportTable {
    std::vector<std::string> headers;
    std::vector<std::string> units;  // empty, or one per header
    std::vector<std::vector<std::string>> rows;
};

struct ReportDocument {
    std::string title;               // page 1 heading and PDF title
    std::vector<std::string> lines;  // summary under the title (camera, settings)
    ReportTable table;               // continued on further pages when it does not fit
    std::vector<std::string> notes;  // under the table (column meanings)
    std::vector<ReportMaskPage> pages;
};

// Throws InvalidInput naming the first problem: an empty title, a table without columns or with
// a row or unit list of another width, a mask page without panels, an empty panel, NaN values,
// or a display range that is not finite with lo < hi.
void validate(const ReportDocument& doc);

// Pages the document takes: the table pages (title, summary, table, notes) then one per mask.
int report_page_count(const ReportDocument& doc);

// The whole report as one PDF file (all pages).
std::string report_pdf(const ReportDocument& doc);

// One SVG file per page (well-formed XML, sizes in pt).
std::vector<std::string> report_svg_pages(const ReportDocument& doc);

// One PNG file per page, pixels_per_point > 0 and at most 8.
std::vector<std::string> report_png_pages(const ReportDocument& doc,
                                          double pixels_per_point = kReportPngPixelsPerPoint);

enum class ReportFormat { kPdf, kSvg, kPng };

// From the file extension (.pdf, .svg, .png, any case); InvalidInput naming `field` otherwise.
ReportFormat report_format(const std::filesystem::path& path, const std::string& field);

// The files a report at `path` is written to: path itself for PDF; for SVG and PNG one file per
// page, "dir/report.svg" -> "dir/report-1.svg", "dir/report-2.svg", ...
std::vector<std::filesystem::path> report_file_paths(const std::filesystem::path& path,
                                                     int page_count);

// (path, bytes) of every file of the report in the format of the path's extension.
std::vector<std::pair<std::filesystem::path, std::string>> render_report(
    const ReportDocument& doc, const std::filesystem::path& path);

}  // namespace pinmask
