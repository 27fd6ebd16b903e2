// `pinmask export`'s flags and how they become ExportOptions (a --vendor preset under explicit
// flags) and the sidecar's plain data.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "design/mask.hpp"
#include "export/export_pipeline.hpp"
#include "io/export_sidecar.hpp"

namespace pinmask::cli {

struct ExportFlags {
    std::string input, output, stem, vendor = "none", shape = "square", chord_tol = "auto",
                                     margin = "10mm", label_id, dxf_layer = "PINMASK",
                                     hierarchy = "auto";
    std::optional<std::string> draw, formats, units, tone, emulsion, frame, grid, circles, kerf,
        hole_side, max_snap_error;
    std::optional<std::size_t> max_vertices;
    std::optional<double> dpi;
    int sides = 8, layer = 1, datatype = 0;
    bool mirror = false, marks = false, label = false, require_drc_clean = false,
         allow_spacing_violations = false, json = false, no_psf = false, psf_npy = false;
};

// Flags over the --vendor preset over the defaults; InvalidInput names the flag.
ExportOptions export_options_from(const ExportFlags& f, const Mask& mask, const std::string& stem);

// The sidecar of an export (files and PSF are added by the caller).
io::ExportSidecar export_sidecar_of(const ExportFlags& f, const Mask& mask, const ExportOptions& o,
                                    const ExportSummary& s);

}  // namespace pinmask::cli
