// Writing a layout in any fabrication format by its FabFormat (export/formats/read_any.hpp), with
// the options of every writer in one place.
#pragma once

#include <string>

#include "export/formats/dxf_writer.hpp"
#include "export/formats/fab_units.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/pdf_writer.hpp"
#include "export/formats/read_any.hpp"
#include "export/layout/film_paint.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

struct WriteOptions {
    GdsOptions gds;  // layer, datatype (its unit is set from `unit`)
    DxfOptions dxf;  // layer (its unit and circles are set from `unit` and `native_circles`)
    PdfOptions pdf;  // margin (its draw mode is set from `draw`)
    double png_dpi = 2400.0;                  // PNG preview resolution
    FabUnit unit = FabUnit::kMicrometre;      // DXF drawing unit, GDSII user unit
    DrawMode draw = DrawMode::kFilm;          // PDF and PNG: the film, or the drawn polygons
    DrawMode svg_draw = DrawMode::kPolygons;  // SVG (a fabrication drawing: polygons by default)
    bool native_circles = false;              // DXF CIRCLE and Gerber flashes for round pinholes
    // GDSII: one structure per pinhole shape referenced per pinhole (SREF), and an array
    // (AREF) of one tile where the pinholes repeat across tiles; false: flat boundaries.
    bool gds_hierarchy = false;
    double tiff_dpi = 25400.0;       // 1-bit plotter raster resolution
    double max_snap_error_nm = 0.0;  // refuse the raster beyond this snapping error (0: none)
};

// The file's bytes (export/formats/svg_writer, gds_writer, dxf_writer, gerber_writer, pdf_writer,
// png_preview). Gerber is always millimetres (format 4.6 = 1 nm; inch Gerber's 1e-6 in steps
// cannot carry the 1 nm grid, and the Gerber spec deprecates inches); SVG and PDF are physical.
std::string write_fabrication_bytes(const Layout& layout, FabFormat format,
                                    const WriteOptions& options = {});

// The units a file of `format` is written in, for the sidecar and reports.
std::string units_of(FabFormat format, FabUnit unit);

}  // namespace pinmask
