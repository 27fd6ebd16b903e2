#include "io/check_files.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/fab_units.hpp"
#include "export/formats/read_any.hpp"
#include "export/pipeline/vendor_presets.hpp"
#include "io/export_sidecar.hpp"
#include "io/mask_json.hpp"
#include "io/sidecar_identity.hpp"

namespace pinmask::io {
namespace {

namespace fs = std::filesystem;

// Between the stages of a check: the time budget (PINMASK_TIME_LIMIT), if spent, stops it.
void poll_time(const std::string& stage) { check_time_limit("check stopped " + stage); }

Mask read_design(const std::string& path) {
    return read_mask_file(path, {.allow_spacing_violations = true});
}

DrcRules overridden(const CheckRequest& q, DrcRules rules) {
    return q.overrides ? q.overrides(rules) : rules;
}

// A picture export wrote (PDF, PNG, 1-bit TIFF): the design rebuilt from the mask and the
// sidecar (or the given settings; a PNG needs the sidecar for its dpi), design-rule checked, and
// the picture compared with it (export/pipeline/file_check check_picture_file).
void check_picture(const CheckRequest& q, const ExportSidecar* side, CheckReport& rep) {
    std::optional<Mask> read;
    if (!q.mask_value && rep.mask.empty())
        throw invalid_field(field_ref("mask"), "''",
                            "a PDF, PNG or TIFF is compared with its design: keep the export "
                            "sidecar (and its mask) beside the file, or give " +
                                field_ref("mask"));
    if (!q.mask_value) read = read_design(rep.mask);
    const Mask& mask = q.mask_value ? *q.mask_value : *read;
    const Layout design = make_layout(mask, check_layout(check_layout_settings(q.layout), side));
    rep.rules = overridden(q, rules_for_mask(mask, rep.vendor, design.grid_nm));
    PictureCheckOptions po;
    po.rules = rep.rules;
    if (side) {
        po.draw = parse_draw_mode(side->draw, "sidecar geometry.draw");
        po.png_dpi = side->png_dpi;
        po.pdf.margin_m = side->pdf_margin_m;
    }
    rep.note =
        "the design (rebuilt from the mask) is design-rule checked; the picture is compared "
        "with it";
    rep.check = check_picture_file(q.input, design, po);
}

}  // namespace

CheckReport run_check(const CheckRequest& q) {
    const bool mask_input = q.input_mask || is_mask_file(q.input);
    // The export sidecar beside a fabrication file gives the vendor's rules (and the layout).
    const fs::path side_path = q.input_mask ? fs::path() : sidecar_path_for(q.input);
    std::optional<ExportSidecar> side;
    if (!mask_input && !q.no_sidecar && fs::is_regular_file(side_path))
        side = read_export_sidecar(side_path);
    CheckReport rep;
    rep.input = q.input;
    if (q.vendor) {
        rep.rules_source = "given";
        rep.vendor = vendor_rules_for(*q.vendor);
    } else if (side) {
        rep.rules_source = "the export sidecar";
        rep.vendor = sidecar_rules(*side);
    } else {
        rep.rules_source = "default (film)";
        rep.vendor = vendor_rules("film");
    }
    rep.mask = q.mask;
    rep.list = q.list;
    const ExportSidecar* s = side ? &*side : nullptr;
    const auto settings_from = [&] {
        if (side) {
            rep.settings = "from " + side_path.string();
            if (rep.mask.empty() && !q.mask_value) rep.mask = sidecar_mask(*side, side_path);
        } else {
            rep.settings = "from the flags (no sidecar " + side_path.filename().string() + ")";
        }
    };
    const RuleOverrides overrides = [&q](DrcRules r) { return overridden(q, r); };
    if (const auto picture = picture_format_of(q.input); picture && !mask_input) {
        rep.kind = fab_format_name(*picture);
        settings_from();
        check_picture(q, s, rep);
    } else if (mask_input) {
        if (!q.mask.empty() || q.mask_value)
            throw invalid_field(field_ref("mask"), q.mask, "only used with a fabrication file");
        rep.kind = "mask";
        std::optional<Mask> read;
        if (!q.input_mask) read = read_design(q.input);
        const Mask& mask = q.input_mask ? *q.input_mask : *read;
        CheckRun run = check_mask(mask, check_layout(check_layout_settings(q.layout), nullptr),
                                  rep.vendor, overrides, q.input);
        rep.check = std::move(run.check);
        rep.rules = run.rules;
        if (!q.spacing_given) rep.spacing = run.spacing;
    } else {
        rep.kind = fs::path(q.input).extension().string().substr(1);
        const FileGeometry file = read_fabrication_file(q.input);
        poll_time("after reading " + q.input);
        settings_from();
        if (side) check_sidecar_unit(*side, file);
        FabricationCheckRequest f;
        f.input = q.input;
        f.vendor = rep.vendor;
        f.overrides = overrides;
        f.max_xor_nm2 = q.max_xor_um2 * 1e6;
        std::optional<Mask> read;
        if (!q.mask_value && !rep.mask.empty()) read = read_design(rep.mask);
        const Mask* mask = q.mask_value ? q.mask_value : read ? &*read : nullptr;
        const LayoutOptions layout = check_layout(check_layout_settings(q.layout), s);
        if (mask) {
            f.layout = layout;
            if (!side) apply_file_declarations(f.layout, file);  // as the file declares them
            f.mask = mask;
            f.whole_layout = side.has_value();
        } else if (side) {
            // No design to build, but the settings given were still compared with the sidecar
            // (check_layout above): a contradiction stops the check whether or not its mask
            // resolves.
            const auto& a = side->active_area_nm;
            const std::int64_t fr = std::llround(side->frame_m * 1e9);
            f.outline = BoxNm{a[0] - fr, a[1] - fr, a[2] + fr, a[3] + fr};
            rep.note = "mask " + side->mask_path +
                       " not found: no comparison; centre spacing only with " +
                       field_ref("min_spacing");
        } else {
            rep.note = "no " + field_ref("mask") +
                       " and no sidecar: all rings are checked as polygons; centre spacing only "
                       "with " +
                       field_ref("min_spacing");
        }
        f.film =
            film_identity_expected(q.input, s, side_path, q.no_sidecar, q.vendor, q.layout.tone);
        CheckRun run = check_fabrication(file, f);
        rep.check = std::move(run.check);
        rep.rules = run.rules;
        if (mask && !q.spacing_given) rep.spacing = run.spacing;
        if (!run.unit_assumed.empty() && !side) {
            rep.unit_assumed = run.unit_assumed;
            rep.note = rep.note.empty() ? run.unit_assumed : rep.note + "; " + run.unit_assumed;
        }
    }
    poll_time("before printing the verdict on " + q.input);
    return rep;
}

}  // namespace pinmask::io
