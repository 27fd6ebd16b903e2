// The export sidecar's settings for one export: what `pinmask export` and Python's export_mask
// record in <stem>.export.json beside the fabrication files (io/export_sidecar writes it, and
// check reads its layout back through io/sidecar_layout). Notes are in the library's words
// (fields as references, core/errors/field_names): each face spells them.
#pragma once

#include "design/pattern/mask.hpp"
#include "export/pipeline/export_pipeline.hpp"
#include "export/pipeline/export_request.hpp"
#include "io/export_sidecar.hpp"

namespace pinmask::io {

// The sidecar of an export of `mask` with `request` (its input path recorded as mask_path),
// resolved to `options`, that gave `summary`; the files and PSF entries are the caller's to add.
ExportSidecar export_sidecar_of(const ExportRequest& request, const Mask& mask,
                                const ExportOptions& options, const ExportSummary& summary);

// One fabrication file's entry: its name, format, units, size, FNV-1a 64 hash of the bytes, the
// read-back verification and the format's detail (GDS/OASIS layer/datatype, DXF layer, PNG and
// 1-bit TIFF dots per inch).
ExportSidecarFile sidecar_file_entry(const std::string& name, const ExportedFile& file,
                                     const std::string& verification, const ExportRequest& request,
                                     const ExportOptions& options);

}  // namespace pinmask::io
