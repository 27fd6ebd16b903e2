// `pinmask export` as a library call: a mask and ExportOptions in, the layout, its design-rule
// report and the bytes of every requested fabrication file out (nothing is written or printed;
// the caller stages the files, reads each back with export/pipeline/read_back verify_written, and
// commits them together with a sidecar).
#pragma once

#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "export/formats/read_any.hpp"
#include "export/formats/write_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/pipeline/drc.hpp"

namespace pinmask {

inline constexpr std::size_t kHierarchyAutoPinholes = 10'000;  // `--hierarchy auto` threshold
// The 1-bit raster is refused by default when snapping to the plotter grid changes a pinhole's
// size or centre by more than 5 % of its side: beyond that the film no longer has the designed
// open area (the PSF's pinhole kernel changes by about twice that in energy).
inline constexpr double kDefaultSnapFraction = 0.05;

struct ExportOptions {
    std::vector<FabFormat> formats = {FabFormat::kSvg, FabFormat::kPdf,    FabFormat::kGds,
                                      FabFormat::kDxf, FabFormat::kGerber, FabFormat::kPng};
    LayoutOptions layout;  // shape, size, tone, mirror, frame, marks, label, grid, vertex limit
    WriteOptions write;    // per-format options, unit, draw mode, native circles
    VendorRules drc = vendor_rules("none");  // design-rule preset checked on the layout
    // Violations: RuntimeFailure naming every failed rule, no files. Both faces set it unless
    // the user asks for the files for inspection (export_request's write_on_violations).
    bool require_drc_clean = false;
    // Laser cutting: the beam removes kerf_m of material around its path, so each hole is drawn
    // kerf_m smaller (side or diameter) and comes out at the design size. 0: none.
    double kerf_m = 0.0;
    // Plate the whole extent must fit (square side; 0: no limit), e.g. a 5-inch photomask's
    // quality area.
    double plate_m = 0.0;

    // Throws InvalidInput naming the field, value and rule (no formats, non-finite or negative
    // lengths, a hole side of 0, a dpi out of range...).
    void validate() const;
};

struct ExportedFile {
    FabFormat format;
    std::string extension;  // ".gds", ...
    std::string bytes;
    std::string units;  // what the file's numbers mean (export/formats/write_any units_of)
};

struct ExportSummary {
    Layout layout;
    DrcReport drc;
    std::vector<ExportedFile> files;  // in the order of ExportOptions::formats
    std::vector<std::string> notes;   // choices made on the user's behalf (kerf, fallbacks)
};

// Builds the layout, checks it, writes every format into memory. Throws InvalidInput for bad
// options (validate) or a layout that cannot be made, RuntimeFailure when require_drc_clean is
// set and the check finds violations.
ExportSummary export_mask(const Mask& mask, const ExportOptions& options);

}  // namespace pinmask
