#include "io/export_sidecar_of.hpp"

#include "export/formats/fab_units.hpp"
#include "export/formats/read_any.hpp"
#include "export/layout/film_paint.hpp"
#include "export/layout/geometry.hpp"
#include "io/fnv1a.hpp"

namespace pinmask::io {

ExportSidecar export_sidecar_of(const ExportRequest& f, const Mask& mask, const ExportOptions& o,
                                const ExportSummary& s) {
    ExportSidecar d;
    const Layout& l = s.layout;
    d.mask_path = f.input;
    d.geometry_hash = l.mask_hash;
    d.n = mask.pattern.n;
    d.tiles_rows = mask.pattern.tiles_rows;
    d.tiles_cols = mask.pattern.tiles_cols;
    d.pinholes = mask.pattern.pinholes.size();
    d.pinhole_m = mask.camera.pinhole_m;
    d.grid_nm = l.grid_nm;
    d.tone = tone_name(l.tone);
    d.mirrored = l.mirrored;
    d.unit = fab_unit_name(o.write.unit);
    d.shape = f.shape;
    d.sides = d.drawn_sides = l.hole_sides;
    // The pitch on the grid when the holes are the whole cell (export/layout/geometry).
    d.hole_side_m = o.layout.hole_side_m > 0 ? o.layout.hole_side_m : double(l.pitch_nm) * 1e-9;
    if (o.kerf_m > 0) d.hole_side_m -= o.kerf_m;
    d.chord_tolerance_m = o.layout.chord_tolerance_m;
    d.frame_m = o.layout.frame_m;
    d.marks = o.layout.marks;
    d.label = o.layout.label_lines;
    d.max_vertices = o.layout.max_vertices;
    d.draw = draw_mode_name(o.write.draw);
    d.svg_draw = draw_mode_name(o.write.svg_draw);
    d.circles = o.write.native_circles && !l.circles.empty() ? "native" : "polygon";
    d.hierarchy = o.write.gds_hierarchy ? "cells" : "flat";
    d.kerf_m = o.kerf_m;
    d.png_dpi = o.write.png_dpi;
    d.pdf_margin_m = o.write.pdf.margin_m;
    d.active_area_nm = {l.active_area.x0, l.active_area.y0, l.active_area.x1, l.active_area.y1};
    d.extent_nm = {l.extent.x0, l.extent.y0, l.extent.x1, l.extent.y1};
    d.polygons = l.polygons.size();
    d.annotations = l.annotations.size();
    d.vendor = f.vendor;
    d.rules_name = o.drc.name;
    d.rules_min_feature_nm = o.drc.min_feature_nm;
    d.rules_min_space_nm = o.drc.min_gap_nm;
    d.rules_max_vertices = o.drc.max_vertices;
    d.drc_clean = s.drc.clean();
    d.drc_counts = s.drc.counts;
    d.psf_absent = "not written (the export was asked for no PSF files)";
    d.notes = s.notes;  // the library's words: each face spells the fields
    return d;
}

ExportSidecarFile sidecar_file_entry(const std::string& name, const ExportedFile& e,
                                     const std::string& verification, const ExportRequest& f,
                                     const ExportOptions& o) {
    std::string detail;
    if (e.format == FabFormat::kGds || e.format == FabFormat::kOasis)
        detail = "layer " + std::to_string(f.layer) + "/" + std::to_string(f.datatype);
    if (e.format == FabFormat::kDxf) detail = "layer " + f.dxf_layer;
    if (e.format == FabFormat::kPng) detail = std::to_string(o.write.png_dpi) + " dpi";
    if (e.format == FabFormat::kTiff1) detail = std::to_string(o.write.tiff_dpi) + " dpi";
    return {name,           fab_format_name(e.format), e.units,
            e.bytes.size(), fnv1a64_hex(e.bytes),      verification,
            detail};
}

}  // namespace pinmask::io
