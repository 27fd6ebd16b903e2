#include "report/report.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <map>
#include <memory>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"
#include "core/version.hpp"
#include "export/layout/film_paint.hpp"
#include "report/report_draw.hpp"
#include "report/report_pages.hpp"

namespace pinmask {
namespace {

constexpr char kPinnedDate[] = "2000-01-01T00:00:00Z";  // as export/formats/pdf_writer
constexpr double kMaxPixelsPerPoint = 8.0;              // 576 dpi: 6736 x 4762 px pages
const report_draw::Font kFooterFont{7.5, false, false};
constexpr double kFooterBaselineFromBottom = 24.0;

using cairo::ContextPtr;
using cairo::SurfacePtr;

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

// Draws page `index` (0-based) of the document on a white page.
using PageDrawer = std::function<void(cairo_t*, int)>;

PageDrawer page_drawer(const ReportDocument& doc, int& page_count) {
    auto table_pages =
        std::make_shared<std::vector<report_pages::TablePage>>(report_pages::plan_table_pages(doc));
    const int total = static_cast<int>(table_pages->size() + doc.pages.size());
    page_count = total;
    return [&doc, table_pages, total](cairo_t* cr, int index) {
        cairo_save(cr);
        cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_paint(cr);
        cairo_restore(cr);
        const std::size_t i = static_cast<std::size_t>(index);
        if (i < table_pages->size()) {
            report_pages::draw_table_page(cr, doc, (*table_pages)[i]);
        } else {
            report_pages::draw_mask_page(cr, doc.pages[i - table_pages->size()]);
        }
        report_draw::prepare_context(cr);
        report_draw::draw_text(
            cr, kReportPageWidthPt / 2, kReportPageHeightPt - kFooterBaselineFromBottom,
            doc.title + "  -  page " + std::to_string(index + 1) + " of " + std::to_string(total),
            kFooterFont, 0.5);
        check_cairo(cr, "report page " + std::to_string(index + 1));
    };
}

// Replaces the numbers of Cairo's process-wide ids ("image<N>", "surface<N>", where written as
// id="..." or referenced as "#...") by 1, 2, ... in order of first appearance per prefix. Only
// those two contexts are touched: '"' and '#' never occur in the base64 image data.
std::string renumber_svg_ids(const std::string& svg) {
    static const char* const kPrefixes[] = {"image", "surface"};
    std::map<std::string, std::map<std::string, int>> ids;  // prefix -> old number -> new
    std::string out;
    out.reserve(svg.size());
    std::size_t i = 0;
    while (i < svg.size()) {
        const bool after_id = i >= 4 && svg.compare(i - 4, 4, "id=\"") == 0;
        const bool after_hash = i >= 1 && svg[i - 1] == '#';
        bool replaced = false;
        if (after_id || after_hash) {
            for (const char* prefix : kPrefixes) {
                const std::string p = prefix;
                if (svg.compare(i, p.size(), p) != 0) continue;
                std::size_t j = i + p.size();
                while (j < svg.size() && std::isdigit(static_cast<unsigned char>(svg[j]))) ++j;
                if (j == i + p.size()) continue;
                auto& table = ids[p];
                const std::string old = svg.substr(i + p.size(), j - i - p.size());
                const auto it = table.emplace(old, static_cast<int>(table.size()) + 1).first;
                out += p + std::to_string(it->second);
                i = j;
                replaced = true;
                break;
            }
        }
        if (!replaced) out += svg[i++];
    }
    return out;
}

void check_panel(const ReportPanel& p, const std::string& where) {
    if (p.values.size() == 0) throw InvalidInput(where + ": the panel has no pixels");
    if (p.values.isNaN().any()) throw InvalidInput(where + ": the panel has NaN values");
    if (!std::isfinite(p.lo) || !std::isfinite(p.hi) || !(p.lo < p.hi)) {
        throw invalid_field(
            where + " display range",
            report_draw::short_number(p.lo) + " .. " + report_draw::short_number(p.hi),
            "must be finite with lo < hi");
    }
}

}  // namespace

void validate(const ReportDocument& doc) {
    if (doc.title.empty()) throw InvalidInput("report title: must not be empty");
    const ReportTable& t = doc.table;
    if (t.headers.empty()) throw InvalidInput("report table: needs at least one column");
    if (!t.units.empty() && t.units.size() != t.headers.size()) {
        throw invalid_field(
            "report table units", std::to_string(t.units.size()),
            "must be empty or one per header (" + std::to_string(t.headers.size()) + ")");
    }
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
        if (t.rows[r].size() != t.headers.size()) {
            throw invalid_field(
                "report table row " + std::to_string(r + 1),
                std::to_string(t.rows[r].size()) + " cells",
                "must have one cell per header (" + std::to_string(t.headers.size()) + ")");
        }
    }
    for (std::size_t i = 0; i < doc.pages.size(); ++i) {
        const std::string where = "report mask page " + std::to_string(i + 1);
        if (doc.pages[i].panels.empty()) throw InvalidInput(where + ": needs at least one panel");
        for (std::size_t k = 0; k < doc.pages[i].panels.size(); ++k)
            check_panel(doc.pages[i].panels[k], where + " panel " + std::to_string(k + 1));
    }
}

int report_page_count(const ReportDocument& doc) {
    validate(doc);
    return static_cast<int>(report_pages::plan_table_pages(doc).size() + doc.pages.size());
}

std::string report_pdf(const ReportDocument& doc) {
    validate(doc);
    int pages = 0;
    const PageDrawer draw = page_drawer(doc, pages);
    std::string out;
    {
        SurfacePtr surface(cairo_pdf_surface_create_for_stream(append, &out, kReportPageWidthPt,
                                                               kReportPageHeightPt));
        check_cairo_surface(surface.get(), "report PDF surface");
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, doc.title.c_str());
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR,
                                       "pinmask " PINMASK_VERSION);
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, kPinnedDate);
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_MOD_DATE, kPinnedDate);
        ContextPtr cr(cairo_create(surface.get()));
        for (int p = 0; p < pages; ++p) {
            draw(cr.get(), p);
            cairo_show_page(cr.get());
        }
        check_cairo(cr.get(), "report PDF");
        cr.reset();
        cairo_surface_finish(surface.get());
        check_cairo_surface(surface.get(), "report PDF output");
    }
    return out;
}

std::vector<std::string> report_svg_pages(const ReportDocument& doc) {
    validate(doc);
    int pages = 0;
    const PageDrawer draw = page_drawer(doc, pages);
    std::vector<std::string> out;
    for (int p = 0; p < pages; ++p) {
        std::string svg;
        {
            SurfacePtr surface(cairo_svg_surface_create_for_stream(append, &svg, kReportPageWidthPt,
                                                                   kReportPageHeightPt));
            check_cairo_surface(surface.get(), "report SVG surface");
            cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PT);
            ContextPtr cr(cairo_create(surface.get()));
            draw(cr.get(), p);
            cr.reset();
            cairo_surface_finish(surface.get());
            check_cairo_surface(surface.get(), "report SVG output");
        }
        out.push_back(renumber_svg_ids(svg));
    }
    return out;
}

std::vector<std::string> report_png_pages(const ReportDocument& doc, double pixels_per_point) {
    if (!(pixels_per_point > 0.0) || !(pixels_per_point <= kMaxPixelsPerPoint)) {
        throw invalid_field("pixels_per_point", report_draw::short_number(pixels_per_point),
                            "must be > 0 and <= 8");
    }
    validate(doc);
    int pages = 0;
    const PageDrawer draw = page_drawer(doc, pages);
    const int w = static_cast<int>(std::ceil(kReportPageWidthPt * pixels_per_point));
    const int h = static_cast<int>(std::ceil(kReportPageHeightPt * pixels_per_point));
    std::vector<std::string> out;
    for (int p = 0; p < pages; ++p) {
        SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h));
        check_cairo_surface(surface.get(), "report PNG surface");
        {
            ContextPtr cr(cairo_create(surface.get()));
            cairo_scale(cr.get(), pixels_per_point, pixels_per_point);
            draw(cr.get(), p);
        }
        std::string png;
        if (cairo_surface_write_to_png_stream(surface.get(), append, &png) !=
            CAIRO_STATUS_SUCCESS) {
            throw RuntimeFailure("report PNG page " + std::to_string(p + 1) +
                                 ": cairo could not encode it");
        }
        out.push_back(std::move(png));
    }
    return out;
}

ReportFormat report_format(const std::filesystem::path& path, const std::string& field) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".pdf") return ReportFormat::kPdf;
    if (ext == ".svg") return ReportFormat::kSvg;
    if (ext == ".png") return ReportFormat::kPng;
    throw invalid_field(field, path.string(),
                        "must end in .pdf (one file), .svg or .png (one file per page)");
}

std::vector<std::filesystem::path> report_file_paths(const std::filesystem::path& path,
                                                     int page_count) {
    if (report_format(path, "report path") == ReportFormat::kPdf) return {path};
    std::vector<std::filesystem::path> out;
    for (int p = 1; p <= page_count; ++p) {
        std::filesystem::path f = path;
        f.replace_filename(path.stem().string() + "-" + std::to_string(p) +
                           path.extension().string());
        out.push_back(f);
    }
    return out;
}

std::vector<std::pair<std::filesystem::path, std::string>> render_report(
    const ReportDocument& doc, const std::filesystem::path& path) {
    const ReportFormat format = report_format(path, "report path");
    std::vector<std::string> bytes;
    if (format == ReportFormat::kPdf) {
        bytes.push_back(report_pdf(doc));
    } else if (format == ReportFormat::kSvg) {
        bytes = report_svg_pages(doc);
    } else {
        bytes = report_png_pages(doc);
    }
    const auto paths = report_file_paths(path, static_cast<int>(bytes.size()));
    std::vector<std::pair<std::filesystem::path, std::string>> out;
    for (std::size_t i = 0; i < bytes.size(); ++i) out.emplace_back(paths[i], std::move(bytes[i]));
    return out;
}

}  // namespace pinmask
