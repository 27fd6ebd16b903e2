#include "io/sidecar_layout.hpp"

#include <cmath>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "export/formats/fab_units.hpp"
#include "export/layout/shapes.hpp"
#include "export/pipeline/vendor_presets.hpp"

namespace pinmask::io {

namespace fs = std::filesystem;

CheckLayoutSettings check_layout_settings(const CheckLayoutText& given) {
    const auto length = [](const std::optional<std::string>& v,
                           const std::string& field) -> std::optional<GivenLength> {
        if (!v) return std::nullopt;
        return GivenLength{parse_length_m(*v, field), *v};
    };
    CheckLayoutSettings g;
    g.shape = given.shape;
    if (given.sides && (*given.sides < 3 || *given.sides > kMaxPolygonSides))
        throw invalid_field(field_ref("sides"), std::to_string(*given.sides),
                            "must be in 3.." + std::to_string(kMaxPolygonSides));
    g.sides = given.sides;
    g.hole_side = length(given.hole_side, field_ref("hole_side"));
    g.frame = length(given.frame, field_ref("frame"));
    g.chord_tol = length(given.chord_tol, field_ref("chord_tol"));
    g.tone = given.tone;
    g.units = given.units;
    g.mirror = given.mirror;
    return g;
}

LayoutOptions check_layout(const CheckLayoutSettings& o, const ExportSidecar* side) {
    LayoutOptions lo;
    auto agree = [&](const std::string& field, const std::string& given,
                     const std::string& recorded, bool same) {
        if (!same)
            throw invalid_field(field, given,
                                "disagrees with the export sidecar, which records " + recorded +
                                    " (omit the flag to use the sidecar, or " +
                                    field_ref("no_sidecar") + ")");
    };
    if (side) {
        lo.tone = parse_tone(side->tone, "sidecar geometry.tone");
        lo.mirror = side->mirrored;
        lo.shape = parse_hole_shape(side->shape, "sidecar geometry.shape");
        lo.polygon_sides = side->drawn_sides;
        lo.hole_side_m = side->hole_side_m;
        lo.chord_tolerance_m = side->chord_tolerance_m;
        lo.frame_m = side->frame_m;
        lo.marks = side->marks;
        lo.label_lines = side->label;
        lo.max_vertices = side->max_vertices;
        lo.grid_m = double(side->grid_nm) * 1e-9;
    }
    auto length = [&](const std::optional<GivenLength>& v, const std::string& name, double& field) {
        if (!v) return;
        if (side)
            agree(name, v->text, std::to_string(field) + " m", std::fabs(v->m - field) <= 1e-12);
        field = v->m;
    };
    length(o.hole_side, field_ref("hole_side"), lo.hole_side_m);
    length(o.frame, field_ref("frame"), lo.frame_m);
    length(o.chord_tol, field_ref("chord_tol"), lo.chord_tolerance_m);
    if (o.shape) {
        const HoleShape s = parse_hole_shape(*o.shape, field_ref("shape"));
        if (side) agree(field_ref("shape"), *o.shape, side->shape, s == lo.shape);
        lo.shape = s;
    }
    if (o.sides) {
        // A shape without sides to set would ignore the value: refused, as export refuses it.
        if (lo.shape != HoleShape::kPolygon)
            throw invalid_field(field_ref("sides"), std::to_string(*o.sides),
                                "sets the sides of " + field_ref("shape") +
                                    " polygon; the design's shape is " +
                                    (side ? side->shape + " (the export sidecar)"
                                          : std::string(o.shape ? *o.shape : "square")) +
                                    ", which it would not change");
        if (side)
            agree(field_ref("sides"), std::to_string(*o.sides), std::to_string(side->drawn_sides),
                  *o.sides == side->drawn_sides);
        lo.polygon_sides = *o.sides;
    }
    if (o.tone) {
        const Tone t = parse_tone(*o.tone, field_ref("tone"));
        if (side) agree(field_ref("tone"), *o.tone, side->tone, t == lo.tone);
        lo.tone = t;
    }
    if (o.mirror) {
        if (side) agree(field_ref("mirror"), "given", "not mirrored", side->mirrored);
        lo.mirror = true;
    }
    if (o.units && side) agree(field_ref("units"), *o.units, side->unit, *o.units == side->unit);
    return lo;
}

void apply_file_declarations(LayoutOptions& lo, const FileGeometry& file) {
    const auto& info = file.info;
    if (auto it = info.find("tone"); it != info.end()) lo.tone = parse_tone(it->second, "tone");
    if (auto it = info.find("mirrored"); it != info.end()) lo.mirror = it->second == "yes";
    if (auto it = info.find("grid_nm"); it != info.end())
        lo.grid_m = parse_number(it->second, "grid_nm") * 1e-9;
}

VendorRules sidecar_rules(const ExportSidecar& side) {
    if (side.rules_name.empty()) return vendor_rules_for(side.vendor);
    VendorRules r;
    r.name = side.rules_name;
    r.description = "as the export checked them (sidecar)";
    r.min_feature_nm = side.rules_min_feature_nm;
    r.min_gap_nm = side.rules_min_space_nm;
    r.max_vertices = side.rules_max_vertices;
    return r;
}

void check_sidecar_unit(const ExportSidecar& side, const FileGeometry& file) {
    const auto u = file.info.find("unit_nm");
    if (u != file.info.end() &&
        std::to_string(nm_per_unit(parse_fab_unit(side.unit, "sidecar unit"))) != u->second)
        throw invalid_field("file unit", u->second + " nm",
                            "disagrees with the sidecar's unit " + side.unit);
}

std::string sidecar_mask(const ExportSidecar& side, const fs::path& sidecar) {
    for (const fs::path& p : {fs::path(side.mask_path), sidecar.parent_path() / side.mask_path,
                              sidecar.parent_path() / fs::path(side.mask_path).filename()})
        if (fs::is_regular_file(p)) return p.string();
    return "";
}

}  // namespace pinmask::io
