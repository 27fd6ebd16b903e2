// `pinmask export`'s settings (export/pipeline/export_request.hpp) and the sidecar's plain data.
#pragma once

#include "design/pattern/mask.hpp"
#include "export/pipeline/export_pipeline.hpp"
#include "export/pipeline/export_request.hpp"
#include "io/export_sidecar.hpp"

namespace pinmask::cli {

// The settings as parsed (export/pipeline/export_request.hpp).
using ExportFlags = ExportRequest;
using pinmask::export_options_from;

// The sidecar of an export (files and PSF are added by the caller).
io::ExportSidecar export_sidecar_of(const ExportFlags& f, const Mask& mask, const ExportOptions& o,
                                    const ExportSummary& s);

}  // namespace pinmask::cli
