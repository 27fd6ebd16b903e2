#include "cli/check_settings.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/units.hpp"

namespace pinmask::cli {

namespace fs = std::filesystem;

// Layout settings: the sidecar's, with every explicit flag required to agree; or the flags.
LayoutOptions design_options(const CheckOptions& o, const io::ExportSidecar* side) {
    LayoutOptions lo;
    auto agree = [&](const char* flag, const std::string& given, const std::string& recorded,
                     bool same) {
        if (!same)
            throw invalid_field(flag, given,
                                "disagrees with the export sidecar, which records " + recorded +
                                    " (omit the flag to use the sidecar, or --no-sidecar)");
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
    auto length = [&](const std::optional<std::string>& v, const char* flag, double& field) {
        if (!v) return;
        const double m = parse_length_m(*v, flag);
        if (side) agree(flag, *v, std::to_string(field) + " m", std::fabs(m - field) <= 1e-12);
        field = m;
    };
    length(o.hole_side, "--hole-side", lo.hole_side_m);
    length(o.frame, "--frame", lo.frame_m);
    length(o.chord_tol, "--chord-tol", lo.chord_tolerance_m);
    if (o.shape) {
        const HoleShape s = parse_hole_shape(*o.shape, "--shape");
        if (side) agree("--shape", *o.shape, side->shape, s == lo.shape);
        lo.shape = s;
    }
    if (o.sides) {
        if (side && lo.shape == HoleShape::kPolygon)
            agree("--sides", std::to_string(*o.sides), std::to_string(side->drawn_sides),
                  *o.sides == side->drawn_sides);
        lo.polygon_sides = *o.sides;
    }
    if (o.tone) {
        const Tone t = parse_tone(*o.tone, "--tone");
        if (side) agree("--tone", *o.tone, side->tone, t == lo.tone);
        lo.tone = t;
    }
    if (o.mirror) {
        if (side) agree("--mirror", "given", "not mirrored", side->mirrored);
        lo.mirror = true;
    }
    if (o.units && side) agree("--units", *o.units, side->unit, *o.units == side->unit);
    return lo;
}

// The mask a sidecar names: its path as recorded, else relative to the sidecar's folder.
std::string sidecar_mask(const io::ExportSidecar& side, const fs::path& sidecar) {
    for (const fs::path& p : {fs::path(side.mask_path), sidecar.parent_path() / side.mask_path,
                              sidecar.parent_path() / fs::path(side.mask_path).filename()})
        if (fs::is_regular_file(p)) return p.string();
    return "";
}

namespace {

std::int64_t length_nm(const std::string& text, const char* flag, std::int64_t min_nm) {
    const double nm = std::round(parse_length_m(text, flag) * 1e9);
    if (!(nm >= double(min_nm)) || nm > 1e12) {
        throw invalid_field(flag, text,
                            "must be between " + std::to_string(min_nm) + " nm and 1e12 nm (1 km)");
    }
    return static_cast<std::int64_t>(nm);
}

}  // namespace

DrcRules resolve_rules(const CheckOptions& o, DrcRules rules) {
    if (o.min_gap) rules.min_gap_nm = length_nm(*o.min_gap, "--min-gap", 1);
    if (o.min_feature) rules.min_feature_nm = length_nm(*o.min_feature, "--min-feature", 0);
    if (o.min_spacing) {
        rules.min_center_spacing_nm = double(length_nm(*o.min_spacing, "--min-spacing", 0));
    }
    if (o.max_vertices) rules.max_vertices = *o.max_vertices;
    rules.max_reported_per_rule = o.list;
    return rules;
}

}  // namespace pinmask::cli
