#include "export/pipeline/export_request.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "export/layout/shapes.hpp"
#include "export/pipeline/vendor_presets.hpp"

namespace pinmask {
namespace {

using std::string;

std::vector<FabFormat> parse_formats(const string& list) {
    std::vector<FabFormat> out;
    std::stringstream ss(list);
    for (string item; std::getline(ss, item, ',');)
        if (!item.empty()) {
            const FabFormat f = parse_fab_format(item, field_ref("formats"));
            if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
        }
    return out;
}

}  // namespace

ExportOptions export_options_from(const ExportRequest& f, const Mask& mask, const string& stem) {
    const VendorPreset* v = find_vendor_preset(f.vendor);
    ExportOptions o;
    LayoutOptions& l = o.layout;
    if (v) {
        o.formats = v->formats;
        o.write.unit = v->unit;
        l.tone = v->tone;
        l.mirror = v->emulsion_down;
        l.frame_m = v->frame_m;
        l.max_vertices = v->max_vertices;
        l.grid_m = v->grid_m;
        o.write.native_circles = v->native_circles;
        o.kerf_m = v->kerf_m;
        o.plate_m = v->plate_m;
        if (v->tiff_dpi > 0) o.write.tiff_dpi = v->tiff_dpi;
    }
    o.drc = vendor_rules(v ? v->drc : f.vendor);
    if (f.min_feature)
        o.drc.min_feature_nm = rule_length_nm(*f.min_feature, field_ref("min_feature"), 0);
    if (f.min_space) o.drc.min_gap_nm = rule_length_nm(*f.min_space, field_ref("min_space"), 1);
    if (f.formats) o.formats = parse_formats(*f.formats);
    if (f.units) o.write.unit = parse_fab_unit(*f.units, field_ref("units"));
    if (f.tone) l.tone = parse_tone(*f.tone, field_ref("tone"));
    if (f.emulsion && *f.emulsion != "up" && *f.emulsion != "down")
        throw invalid_field(field_ref("emulsion"), *f.emulsion, "must be up or down");
    if (f.emulsion && f.mirror && *f.emulsion == "up")
        throw invalid_field(field_ref("emulsion"), "up",
                            "contradicts " + field_ref("mirror") + " (mirrored = emulsion down)");
    if (f.emulsion) l.mirror = *f.emulsion == "down";
    if (f.mirror) l.mirror = true;
    if (f.frame) l.frame_m = parse_length_m(*f.frame, field_ref("frame"));
    if (f.grid) l.grid_m = parse_length_m(*f.grid, field_ref("grid"));
    if (f.max_vertices) l.max_vertices = *f.max_vertices;
    if (f.kerf) o.kerf_m = parse_length_m(*f.kerf, field_ref("kerf"));
    if (f.circles && *f.circles != "native" && *f.circles != "polygon")
        throw invalid_field(field_ref("circles"), *f.circles, "must be native or polygon");
    if (f.circles) o.write.native_circles = *f.circles == "native";
    if (f.dpi) o.write.png_dpi = o.write.tiff_dpi = *f.dpi;
    if (f.max_snap_error)
        o.write.max_snap_error_nm =
            parse_length_m(*f.max_snap_error, field_ref("max_snap_error")) * 1e9;
    l.shape = parse_hole_shape(f.shape, field_ref("shape"));
    // Checked whatever the shape, and refused with a shape that has no sides to set, so a
    // value is never silently ignored.
    if (f.sides && (*f.sides < 3 || *f.sides > kMaxPolygonSides))
        throw invalid_field(field_ref("sides"), std::to_string(*f.sides),
                            "must be in 3.." + std::to_string(kMaxPolygonSides));
    if (f.sides && l.shape != HoleShape::kPolygon)
        throw invalid_field(field_ref("sides"), std::to_string(*f.sides),
                            "sets the sides of " + field_ref("shape") + " polygon; the shape is " +
                                f.shape + ", which it would not change");
    if (f.sides) l.polygon_sides = *f.sides;
    l.marks = f.marks;
    if (f.chord_tol != "auto")
        l.chord_tolerance_m = parse_length_m(f.chord_tol, field_ref("chord_tol"));
    if (f.chord_tol != "auto" && !(l.chord_tolerance_m > 0))
        throw invalid_field(field_ref("chord_tol"), f.chord_tol, "must be > 0 (or auto)");
    if (f.hole_side) {
        l.hole_side_m = parse_length_m(*f.hole_side, field_ref("hole_side"));
        if (!(l.hole_side_m > 0))
            throw invalid_field(field_ref("hole_side"), *f.hole_side,
                                "must be > 0 (omit it for the cell)");
    }
    if (f.label) {
        l.label_lines = default_label_lines(mask, f.label_id.empty() ? stem : f.label_id);
        l.label_lines.push_back(tone_label_line(l.tone, l.mirror, fab_unit_name(o.write.unit)));
    }
    if (f.draw) o.write.draw = o.write.svg_draw = parse_draw_mode(*f.draw, field_ref("draw"));
    if (f.hierarchy != "auto" && f.hierarchy != "flat" && f.hierarchy != "cells")
        throw invalid_field(field_ref("hierarchy"), f.hierarchy, "must be auto, flat or cells");
    const std::size_t holes = mask.pattern.pinholes.size() *
                              std::size_t(mask.pattern.tiles_rows * mask.pattern.tiles_cols);
    o.write.gds_hierarchy =
        f.hierarchy == "cells" || (f.hierarchy == "auto" && holes > kHierarchyAutoPinholes);
    o.write.gds = {.layer = f.layer, .datatype = f.datatype};
    o.write.dxf = {.layer = f.dxf_layer};
    o.write.pdf.margin_m = parse_length_m(f.margin, field_ref("margin"));
    if (f.require_drc_clean && f.write_on_violations)
        throw InvalidInput(field_ref("write_on_violations") +
                           " writes the files of a failed "
                           "design-rule check, " +
                           field_ref("require_drc_clean") + " writes none: give one of them");
    o.require_drc_clean = !f.write_on_violations;
    return o;
}

std::int64_t rule_length_nm(const string& text, const string& field, std::int64_t min_nm) {
    const double nm = std::round(parse_length_m(text, field) * 1e9);
    if (!(nm >= double(min_nm)) || nm > double(std::int64_t{1} << 31))
        throw invalid_field(field, text,
                            "must be between " + std::to_string(min_nm) + " nm and 2^31 nm");
    return static_cast<std::int64_t>(nm);
}

}  // namespace pinmask
