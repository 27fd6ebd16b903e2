#include "export/formats/pdf_writer.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"
#include "core/version.hpp"
#include "export/formats/decimal.hpp"
#include "export/layout/film_paint.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/marks.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {
namespace {

constexpr double kPointsPerNm = kPdfPointsPerNm;
constexpr std::int64_t kTextPixelNm = 100'000;   // title font pixel: 0.1 mm (0.7 mm capitals)
constexpr std::int64_t kTextGapNm = 20'000;      // gap between font bars
constexpr std::int64_t kBarHeightNm = 250'000;   // scale bar thickness
constexpr std::int64_t kBlockGapNm = 3'000'000;  // film extent to scale bar, bar to title
constexpr double kMaxPagePoints = 14400;         // PDF implementation limit of a page side
constexpr char kPinnedDate[] = "2000-01-01T00:00:00Z";

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

std::string length_text(std::int64_t nm) {
    std::string s;
    if (nm >= 1'000'000) {
        append_scaled(s, nm, 6);
        return s + " MM";
    }
    append_scaled(s, nm, 3);
    return s + " UM";
}

}  // namespace

std::int64_t scale_bar_nm(std::int64_t width_nm) {
    std::int64_t best = 1;
    for (std::int64_t p = 1; p <= width_nm; p *= 10)
        for (std::int64_t m : {1, 2, 5})
            if (m * p * 2 <= width_nm) best = std::max(best, m * p);
    return best;
}

std::vector<std::string> default_title_lines(const Layout& layout, DrawMode draw) {
    const bool clear = layout.tone == Tone::kClear;
    return {label_text("PINMASK MASK H " + layout.mask_hash),
            std::string("TONE ") + (clear ? "CLEAR" : "DARK") +
                (draw == DrawMode::kFilm ? ": BLACK = OPAQUE, WHITE = CLEAR"
                                         : ": DRAWN POLYGONS IN BLACK, NOT THE FILM"),
            std::string("MIRRORED ") + (layout.mirrored ? "YES - FILM SIDE DOWN" : "NO"),
            "SCALE 1:1 - PRINT AT 100 PERCENT", "GRID " + std::to_string(layout.grid_nm) + " NM"};
}

PdfDrawing pdf_drawing(const Layout& layout, const PdfOptions& o) {
    if (!(o.margin_m >= 0) || !std::isfinite(o.margin_m))
        throw invalid_field("margin", std::to_string(o.margin_m), "must be >= 0");
    const std::int64_t margin = std::llround(o.margin_m * 1e9);
    const BoxNm& e = layout.extent;
    std::vector<std::string> lines =
        o.title_lines.empty() ? default_title_lines(layout, o.draw) : o.title_lines;
    for (std::string& l : lines) l = label_text(l);

    // Everything below the film, in layout nanometres (y up).
    const std::int64_t bar = scale_bar_nm(e.x1 - e.x0);
    const std::int64_t bar_top = e.y0 - kBlockGapNm;
    std::vector<Ring> ink{box_ring({e.x0, bar_top - kBarHeightNm, e.x0 + bar, bar_top})};
    const std::vector<Ring> bar_text = text_rings(
        {length_text(bar)}, {e.x0 + bar + kBlockGapNm / 3, bar_top}, kTextPixelNm, kTextGapNm);
    const std::int64_t title_top = bar_top - kBarHeightNm - kBlockGapNm;
    const std::vector<Ring> title = text_rings(lines, {e.x0, title_top}, kTextPixelNm, kTextGapNm);
    ink.insert(ink.end(), bar_text.begin(), bar_text.end());
    ink.insert(ink.end(), title.begin(), title.end());
    const BoxNm page_nm = box_union(
        e, box_union(bounding_box(ink), text_box(lines, {e.x0, title_top}, kTextPixelNm)));
    const double w_pt = double(page_nm.x1 - page_nm.x0 + 2 * margin) * kPointsPerNm;
    const double h_pt = double(page_nm.y1 - page_nm.y0 + 2 * margin) * kPointsPerNm;
    if (w_pt > kMaxPagePoints || h_pt > kMaxPagePoints)
        throw invalid_field("pdf page", std::to_string(w_pt) + " x " + std::to_string(h_pt) + " pt",
                            "is larger than the PDF page limit of 14400 pt (5.08 m)");
    PdfDrawing d{
        .width_pt = w_pt, .height_pt = h_pt, .page_nm = page_nm, .margin_nm = margin, .fills = {}};
    d.fills = film_fills(layout, o.draw);
    d.fills.push_back({false, std::move(ink)});
    return d;
}

std::string pdf_document(const Layout& layout, const PdfOptions& o) {
    const PdfDrawing d = pdf_drawing(layout, o);
    const double w_pt = d.width_pt, h_pt = d.height_pt;
    const std::int64_t margin = d.margin_nm;
    const BoxNm& page_nm = d.page_nm;

    std::string out;
    {
        cairo::SurfacePtr surface(cairo_pdf_surface_create_for_stream(append, &out, w_pt, h_pt));
        check_cairo_surface(surface.get(), "PDF surface");
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE,
                                       ("pinmask mask " + layout.mask_hash).c_str());
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR,
                                       "pinmask " PINMASK_VERSION);
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, kPinnedDate);
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_MOD_DATE, kPinnedDate);
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_SUBJECT,
                                       ("pinmask " + layout_info(layout, "mm")).c_str());
        cairo::ContextPtr cr(cairo_create(surface.get()));
        cairo_set_source_rgb(cr.get(), 1, 1, 1);
        cairo_paint(cr.get());
        cairo_translate(cr.get(), double(margin) * kPointsPerNm, double(margin) * kPointsPerNm);
        cairo_scale(cr.get(), kPointsPerNm, -kPointsPerNm);
        cairo_translate(cr.get(), -double(page_nm.x0), -double(page_nm.y1));
        for (const PdfFill& f : d.fills) fill_rings(cr.get(), f.rings, f.white);
        check_cairo(cr.get(), "PDF drawing");
        cr.reset();
        cairo_surface_finish(surface.get());
        check_cairo_surface(surface.get(), "PDF output");
    }
    return out;
}

}  // namespace pinmask
