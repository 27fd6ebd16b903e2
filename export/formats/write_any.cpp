#include "export/formats/write_any.hpp"

#include "core/errors/error.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/oasis_writer.hpp"
#include "export/formats/plotter_raster.hpp"
#include "export/formats/png_preview.hpp"
#include "export/formats/svg_writer.hpp"

namespace pinmask {

std::string write_fabrication_bytes(const Layout& layout, FabFormat format,
                                    const WriteOptions& options) {
    switch (format) {
        case FabFormat::kSvg:
            return svg_document(layout, options.svg_draw);
        case FabFormat::kGds: {
            GdsOptions g = options.gds;
            g.unit = options.unit;
            g.hierarchy = options.gds_hierarchy;
            return gds_stream(layout, g);
        }
        case FabFormat::kDxf: {
            DxfOptions d = options.dxf;
            d.unit = options.unit;
            d.native_circles = options.native_circles;
            return dxf_document(layout, d);
        }
        case FabFormat::kGerber:
            return gerber_document(layout, options.native_circles);
        case FabFormat::kPdf: {
            PdfOptions p = options.pdf;
            p.draw = options.draw;
            return pdf_document(layout, p);
        }
        case FabFormat::kPng:
            return png_preview(layout, options.png_dpi, options.draw);
        case FabFormat::kOasis:
            return oasis_file(layout, {.layer = options.gds.layer,
                                       .datatype = options.gds.datatype,
                                       .unit = options.unit});
        case FabFormat::kTiff1:
            return plotter_tiff(layout, options.tiff_dpi, options.max_snap_error_nm);
    }
    return {};
}

std::string units_of(FabFormat f, FabUnit unit) {
    switch (f) {
        case FabFormat::kSvg:
            return "viewBox um, size mm";
        case FabFormat::kGds:
            return "database unit 1 nm, user unit 1 " + fab_unit_name(unit);
        case FabFormat::kDxf:
            return fab_unit_name(unit) + " ($INSUNITS " + std::to_string(dxf_insunits(unit)) + ")";
        case FabFormat::kGerber:
            return "mm (format 4.6; Gerber is always mm: inch Gerber cannot carry 1 nm)";
        case FabFormat::kPdf:
            return "pt (1/72 in), scale 1:1";
        case FabFormat::kPng:
            return "pixels";
        case FabFormat::kOasis:
            return "database unit 1 nm (1000 per micron), user unit 1 " + fab_unit_name(unit);
        case FabFormat::kTiff1:
            return "pixels at the plotter's dpi (resolution tags in inches)";
    }
    return "";
}

}  // namespace pinmask
