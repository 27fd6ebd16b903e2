// Reads back the one-page PDF pinmask writes (export/formats/pdf_writer, Cairo's PDF surface) and
// compares it with its design, for `pinmask check`. No PDF library: the reader knows the subset
// Cairo writes for filled paths and refuses everything else by name, never ignores it.
//   File: "%PDF-" header, exactly one /Type /Page with a /MediaBox and one /Contents stream
//   (uncompressed or /FlateDecode via zlib; /Length direct or an indirect object).
//   Content operators: q Q cm (graphics state and matrix), rg g (fill colour), RG G w gs
//   (stroke colour, line width, the alpha state /a0: no effect on fills), m l h re (path), f f*
//   (fill), n (no-op end of path). Any other operator (curves c v y, stroke S, text BT, images
//   Do, clipping W, inline images...) throws InvalidInput naming it.
// Geometry: Cairo keeps path coordinates in 24.8 fixed point device units (rounding error up to
// 1/512 pt) and prints numbers with 3 decimals (0.0005 pt each): a vertex is printed directly
// or, for a rectangle ("x y w h re"), as x + w (two printed numbers), and the page height in
// the y-flip matrix ("1 0 0 -1 0 H cm") is printed too; so a vertex in the file is within
// 1/512 + 3 x 0.0005 pt = 0.00345 pt (1.22 um) of the design's. The comparison allows
// kPdfToleranceNm, a full 1/256 pt (1.38 um); the largest deviation seen on pinmask's files is
// 1.15 um. Features smaller than that are not resolved by a PDF (Cairo may collapse them).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "export/formats/pdf_writer.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

inline constexpr double kPdfToleranceNm = 25.4e6 / 72.0 / 256.0;  // 1/256 pt = 1378 nm

struct PdfPoint {
    double x = 0, y = 0;  // page points, y up (after every cm)
};

struct PdfPathFill {
    double r = 0, g = 0, b = 0;                   // fill colour, 0..1
    std::vector<std::vector<PdfPoint>> subpaths;  // closed or not; move-only subpaths dropped
};

struct PdfPage {
    double width_pt = 0, height_pt = 0;  // the MediaBox
    std::vector<PdfPathFill> fills;      // in paint order
};

// Throws InvalidInput ("pdf: ...") for anything outside the subset above, ResourceLimit when
// the content would not fit the memory budget.
PdfPage read_pdf_page(std::string_view bytes);

struct PdfComparison {
    double width_pt = 0, height_pt = 0, expected_width_pt = 0, expected_height_pt = 0;
    std::size_t fills = 0, expected_fills = 0;
    std::size_t rings = 0, expected_rings = 0;  // over all fills
    std::size_t colour_mismatches = 0;          // fills of the wrong colour
    std::size_t ring_count_mismatches = 0;      // fills with a different number of rings
    std::size_t beyond_tolerance = 0;  // rings further than kPdfToleranceNm from the design's
    double max_deviation_nm = 0.0;     // largest vertex distance found (Hausdorff, see .cpp)
    bool ok() const;
    std::string describe() const;
};

// The page against pdf_drawing(design, options): page size, then fill by fill (after Cairo's
// white page paint) colour, number of rings, and each ring in order within kPdfToleranceNm:
// every vertex and edge midpoint of each ring within the tolerance of the other ring's
// boundary.
PdfComparison compare_pdf(const PdfPage& page, const Layout& design, const PdfOptions& options);

}  // namespace pinmask
