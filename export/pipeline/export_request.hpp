// An export as a user asks for it (the settings of `pinmask export`, text as given, units
// parsed here) and the ExportOptions it becomes: a --vendor preset under the explicit settings.
// Shared by export, check and the Python module; errors name the request's fields
// (core/errors/field_names.hpp).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "design/pattern/mask.hpp"
#include "export/pipeline/export_pipeline.hpp"

namespace pinmask {

struct ExportRequest {
    std::string input, output, stem, vendor = "none", shape = "square", chord_tol = "auto",
                                     margin = "10mm", label_id, dxf_layer = "PINMASK",
                                     hierarchy = "auto";
    std::optional<std::string> draw, formats, units, tone, emulsion, frame, grid, circles, kerf,
        hole_side, max_snap_error;
    // The shop's own limits over the vendor's rule preset (lengths as typed).
    std::optional<std::string> min_feature, min_space;
    std::optional<std::size_t> max_vertices;
    std::optional<double> dpi;
    // Sides of shape polygon (default 8); refused with any other shape, where it would be
    // silently ignored.
    std::optional<int> sides;
    int layer = 1, datatype = 0;
    bool mirror = false, marks = false, label = false, require_drc_clean = false,
         allow_spacing_violations = false, json = false, no_psf = false, psf_npy = false;
    // A design-rule violation fails the export and nothing is written (require_drc_clean, kept
    // for scripts that give it, is that default); write_on_violations writes the files for
    // inspection all the same (the faces still report the violations and fail).
    bool write_on_violations = false;
};

// Settings over the `vendor` preset over the defaults; InvalidInput names the field.
ExportOptions export_options_from(const ExportRequest& f, const Mask& mask,
                                  const std::string& stem);

// A design-rule length (min_feature, min_space) in whole nm: the text parsed as a length,
// at least `min_nm` and at most 2^31 nm; InvalidInput naming `field` otherwise.
std::int64_t rule_length_nm(const std::string& text, const std::string& field, std::int64_t min_nm);

}  // namespace pinmask
