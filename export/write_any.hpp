// Writing a layout in any fabrication format by its FabFormat (export/read_any.hpp), with the
// options of every writer in one place.
#pragma once

#include <string>

#include "export/dxf_writer.hpp"
#include "export/gds_writer.hpp"
#include "export/layout.hpp"
#include "export/pdf_writer.hpp"
#include "export/read_any.hpp"

namespace pinmask {

struct WriteOptions {
    GdsOptions gds;
    DxfOptions dxf;
    PdfOptions pdf;
    double png_dpi = 2400.0;  // PNG preview resolution
};

// The file's bytes (export/svg_writer, gds_writer, dxf_writer, gerber_writer, pdf_writer,
// png_preview).
std::string write_fabrication_bytes(const Layout& layout, FabFormat format,
                                    const WriteOptions& options = {});

}  // namespace pinmask
