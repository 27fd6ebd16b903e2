#include "export/pipeline/export_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/number_format.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/optics/working_distance.hpp"
#include "export/formats/klayout_open.hpp"
#include "export/formats/png_preview.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/shapes.hpp"
#include "export/pipeline/vendor_presets.hpp"

namespace pinmask {
namespace {

void check_length(double v_m, const std::string& field, bool zero_ok) {
    if (!std::isfinite(v_m) || v_m < 0 || (!zero_ok && v_m == 0) || v_m > 1.0)
        throw invalid_field(field, nm_text(v_m * 1e9),
                            zero_ok ? "must be finite, >= 0 and at most 1 m"
                                    : "must be finite, > 0 and at most 1 m");
}

// The drawn width of one pinhole, as the file has it: a native circle's diameter, else the
// width of the first clear pinhole polygon (all pinholes are one shape moved by whole
// pitches, export/layout/geometry). Dark tone draws opaque pieces around the holes: nullopt.
std::optional<std::int64_t> drawn_hole_nm(const Layout& layout) {
    if (!layout.circles.empty()) return layout.circles.front().diameter_nm;
    if (layout.tone != Tone::kClear || layout.polygons.empty()) return std::nullopt;
    std::int64_t x0 = layout.polygons.front().front().x, x1 = x0;
    for (const PointNm& p : layout.polygons.front()) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
    }
    return x1 - x0;
}

}  // namespace

void ExportOptions::validate() const {
    if (formats.empty()) throw invalid_field(field_ref("formats"), "''", "names no format");
    const LayoutOptions& l = layout;
    if (l.hole_side_m != 0.0) check_length(l.hole_side_m, field_ref("hole_side_m"), false);
    check_length(l.frame_m, field_ref("frame_m"), true);
    check_length(kerf_m, field_ref("kerf_m"), true);
    check_length(plate_m, field_ref("plate_m"), true);
    check_length(write.pdf.margin_m, field_ref("margin_m"), true);
    if (!(l.grid_m > 0) || !std::isfinite(l.grid_m) || l.grid_m > 1e-3)
        throw invalid_field(field_ref("grid_m"), nm_text(l.grid_m * 1e9),
                            "must be > 0 and at most 1 mm");
    if (!std::isfinite(l.chord_tolerance_m) || l.chord_tolerance_m < 0 ||
        l.chord_tolerance_m > 1e-3)
        throw invalid_field(field_ref("chord_tolerance_m"), nm_text(l.chord_tolerance_m * 1e9),
                            "must be > 0 and at most 1 mm (or auto)");
    if (l.shape == HoleShape::kPolygon && (l.polygon_sides < 3 || l.polygon_sides > 8000))
        throw invalid_field(field_ref("polygon_sides"), std::to_string(l.polygon_sides),
                            "must be in 3..8000");
    if (l.max_vertices < 8 || l.max_vertices > kGdsHardMaxVertices)
        throw invalid_field(field_ref("max_vertices"), std::to_string(l.max_vertices),
                            "must be in 8..8190 (the GDSII record limit)");
    if (write.gds.layer < 0 || write.gds.layer > 32767)
        throw invalid_field(field_ref("layer"), std::to_string(write.gds.layer),
                            "must be in 0..32767");
    if (write.gds.datatype < 0 || write.gds.datatype > 32767)
        throw invalid_field(field_ref("datatype"), std::to_string(write.gds.datatype),
                            "must be in 0..32767");
    if (!std::isfinite(write.max_snap_error_nm) || write.max_snap_error_nm < 0)
        throw invalid_field(field_ref("max_snap_error_nm"), nm_text(write.max_snap_error_nm),
                            "must be finite and > 0");
    if (!(write.tiff_dpi >= 1 && write.tiff_dpi <= 1e6))
        throw invalid_field(field_ref("tiff_dpi"), format_number(write.tiff_dpi),
                            "must be in 1..1000000");
    if (!(write.png_dpi >= 1 && write.png_dpi <= 1e6))
        throw invalid_field(field_ref("png_dpi"), format_number(write.png_dpi),
                            "must be in 1..1000000");
}

ExportSummary export_mask(const Mask& mask, const ExportOptions& o) {
    o.validate();
    ExportSummary s;
    LayoutOptions lo = o.layout;
    if (o.kerf_m > 0) {
        const double side = lo.hole_side_m > 0 ? lo.hole_side_m : mask.camera.pinhole_m;
        if (!(o.kerf_m < side))
            throw invalid_field(field_ref("kerf_m"), nm_text(o.kerf_m * 1e9),
                                "must be smaller than the hole side " + nm_text(side * 1e9));
        lo.hole_side_m = side - o.kerf_m;
    }
    s.layout = make_layout(mask, lo);
    if (o.kerf_m > 0) {
        // The note states the hole as the file draws it (on the grid), not the side asked for.
        const double side = o.layout.hole_side_m > 0 ? o.layout.hole_side_m : mask.camera.pinhole_m;
        const double asked_nm = lo.hole_side_m * 1e9;
        const std::optional<std::int64_t> drawn = drawn_hole_nm(s.layout);
        std::string note = "kerf " + nm_text(o.kerf_m * 1e9) + ": holes drawn ";
        if (drawn) {
            note += nm_text(double(*drawn));
            if (std::fabs(double(*drawn) - asked_nm) > 1e-6)
                note += " (" + nm_text(asked_nm) + " before the " +
                        nm_text(double(s.layout.grid_nm)) + " grid)";
            note += " (design " + nm_text(side * 1e9) + ") so the cut comes out at " +
                    nm_text(double(*drawn) + o.kerf_m * 1e9);
        } else {
            note += nm_text(asked_nm) + " on the " + nm_text(double(s.layout.grid_nm)) +
                    " grid (design " + nm_text(side * 1e9) + ")";
        }
        s.notes.push_back(note);
    }
    if (const double d_nm = mask.camera.pinhole_m * 1e9;
        std::fabs(double(s.layout.pitch_nm) - d_nm) > 1e-6) {
        // The cells are drawn at the pitch on the grid: say how far that moves the image.
        Camera on_grid = mask.camera;
        on_grid.pinhole_m = double(s.layout.pitch_nm) * 1e-9;
        const double u = mask.camera.object_distance_m;
        const double shift = pixels_per_cell_at(on_grid, u) - pixels_per_cell_at(mask.camera, u);
        char buf[320];
        std::snprintf(buf, sizeof buf,
                      "pinhole side d = %.3f nm is not on the %lld nm grid: cells drawn at pitch "
                      "%lld nm; the pitch at u moves by %+.3g px per cell (%+.3g px across one "
                      "period of %d cells)",
                      d_nm, static_cast<long long>(s.layout.grid_nm),
                      static_cast<long long>(s.layout.pitch_nm), shift, shift * mask.pattern.n,
                      mask.pattern.n);
        s.notes.push_back(buf);
    }
    if (o.plate_m > 0) {
        const BoxNm& e = s.layout.extent;
        const double w = double(e.x1 - e.x0), h = double(e.y1 - e.y0);
        if (std::max(w, h) > o.plate_m * 1e9)
            throw invalid_field(
                field_ref("plate_m"), nm_text(o.plate_m * 1e9),
                "the layout extent " + nm_text(w) + " x " + nm_text(h) +
                    " does not fit the preset's plate (the largest square it writes, this "
                    "side): use fewer tiles, a smaller frame, or a vendor with a larger plate");
    }
    if (o.write.native_circles && s.layout.circles.empty())
        s.notes.push_back(
            field_ref("circles") +
            " native: no round pinholes to draw natively (square or polygon shape, or dark tone, "
            "where pinholes are holes in opaque pieces): polygons written");
    const DrcRules rules = rules_for_mask(mask, o.drc, s.layout.grid_nm);
    s.drc = run_drc(s.layout, rules);
    add_pattern_spacing(s.drc, mask, s.layout.pitch_nm, rules);  // pinholes before merging
    if (o.require_drc_clean && !s.drc.clean()) {
        // Every rule that failed with its count, and the first violation of each in the check's
        // words: the message alone says what to change.
        std::string what;
        for (const auto& [rule, n] : s.drc.counts) {
            what += (what.empty() ? "" : "; ") + rule + " " + std::to_string(n);
            for (const DrcViolation& v : s.drc.violations)
                if (drc_rule_name(v.rule) == rule) {
                    what += " (first: " + v.message + ")";
                    break;
                }
        }
        throw RuntimeFailure(
            "the design-rule check (" + o.drc.name + ": " + vendor_rules_text(o.drc) + ", " +
            spacing_rule_text(mask.pattern.min_spacing_cells, s.layout.pitch_nm, s.layout.grid_nm) +
            ") found violations: " + what + "; nothing is written (" +
            field_ref("write_on_violations") + " writes the files for inspection)");
    }
    WriteOptions w = o.write;
    if (w.max_snap_error_nm == 0) {  // default: 5 % of the drawn pinhole side or diameter
        const double side = lo.hole_side_m > 0 ? lo.hole_side_m : mask.camera.pinhole_m;
        w.max_snap_error_nm = kDefaultSnapFraction * side * 1e9;
    }
    for (FabFormat f : o.formats) {
        s.files.push_back({f, fab_extension(f), write_fabrication_bytes(s.layout, f, w),
                           units_of(f, o.write.unit)});
        // Each file's drawing unit and how to open it at scale in KLayout.
        s.notes.push_back("the " + fab_format_name(f) + " file (" + fab_extension(f) +
                          "): " + klayout_open_text(f, o.write.unit));
    }
    return s;
}

}  // namespace pinmask
