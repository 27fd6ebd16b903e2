// PDF of a layout for film plotters and people, exactly 1:1 (1 pt = 1/72 in; print at 100%):
// the film as it looks (export/layout/film_paint: black opaque, white clear) with a margin, and
// below it, outside the extent, a scale bar and a title block (hash, tone, mirroring, scale), drawn
// with the built-in bar font (export/layout/marks) so no system font is involved. Rendered by
// Cairo's PDF surface with its creation and modification dates pinned
// (cairo_pdf_surface_set_metadata), so the same layout gives the same bytes.
#pragma once

#include <string>
#include <vector>

#include "export/layout/film_paint.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

struct PdfOptions {
    double margin_m = 10e-3;               // white border around everything
    std::vector<std::string> title_lines;  // empty: hash, tone, mirroring and scale
    DrawMode draw = DrawMode::kFilm;       // the film as it looks, or the drawn polygons
};

// The default title block lines for a layout.
std::vector<std::string> default_title_lines(const Layout& layout, DrawMode draw = DrawMode::kFilm);

// What the PDF page holds, in the order it is painted: fills of one colour, each one path of
// rings in layout nanometres (y up). Page point (x, y) of a layout point (y up, as PDF):
// x_pt = (x - page_nm.x0 + margin_nm) * kPdfPointsPerNm, y_pt = (y - page_nm.y0 + margin_nm) *
// kPdfPointsPerNm. The white page itself (Cairo's paint) is not among the fills.
inline constexpr double kPdfPointsPerNm = 72.0 / 25.4e6;
using PdfFill = FilmFill;
struct PdfDrawing {
    double width_pt = 0, height_pt = 0;
    BoxNm page_nm;  // everything drawn, before the margin
    std::int64_t margin_nm = 0;
    std::vector<PdfFill>
        fills;  // film (export/layout/film_paint paint_fills), then scale bar and title
};

// The page's geometry. Throws InvalidInput for a negative margin or a page over 14400 pt.
PdfDrawing pdf_drawing(const Layout& layout, const PdfOptions& options = {});

// The complete PDF file (pdf_drawing painted by Cairo).
std::string pdf_document(const Layout& layout, const PdfOptions& options = {});

// Length of the scale bar for an extent of width w_nm: the largest 1, 2 or 5 x 10^k nm that is
// at most half the width (at least 1 nm).
std::int64_t scale_bar_nm(std::int64_t width_nm);

}  // namespace pinmask
