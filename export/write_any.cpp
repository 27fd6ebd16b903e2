#include "export/write_any.hpp"

#include "export/gerber_writer.hpp"
#include "export/png_preview.hpp"
#include "export/svg_writer.hpp"

namespace pinmask {

std::string write_fabrication_bytes(const Layout& layout, FabFormat format,
                                    const WriteOptions& options) {
    switch (format) {
        case FabFormat::kSvg:
            return svg_document(layout);
        case FabFormat::kGds:
            return gds_stream(layout, options.gds);
        case FabFormat::kDxf:
            return dxf_document(layout, options.dxf);
        case FabFormat::kGerber:
            return gerber_document(layout);
        case FabFormat::kPdf:
            return pdf_document(layout, options.pdf);
        case FabFormat::kPng:
            return png_preview(layout, options.png_dpi);
    }
    return {};
}

}  // namespace pinmask
