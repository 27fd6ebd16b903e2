#include "export/pipeline/check_run.hpp"

#include "core/limits/resource_limits.hpp"
#include "design/optics/fab_grid.hpp"

namespace pinmask {

CheckRun check_mask(const Mask& mask, const LayoutOptions& layout, const VendorRules& vendor,
                    const RuleOverrides& overrides, const std::string& input) {
    CheckRun r;
    r.check.layout = make_layout(mask, layout);
    const Layout& l = r.check.layout;
    check_time_limit("check stopped after building the layout of " + input);
    r.rules = overrides(rules_for_mask(mask, vendor, l.grid_nm));
    r.spacing = spacing_rule_text(mask.pattern.min_spacing_cells, l.pitch_nm, l.grid_nm);
    r.check.drc = run_drc(l, r.rules);
    add_pattern_spacing(r.check.drc, mask, l.pitch_nm, r.rules);  // before the layout's merging
    return r;
}

CheckRun check_fabrication(const FileGeometry& file, const FabricationCheckRequest& q) {
    CheckRun r;
    FileCheckOptions fo;
    fo.max_xor_nm2 = q.max_xor_nm2;
    std::optional<Layout> design;
    if (q.mask) {
        design = make_layout(*q.mask, q.layout);
        fo.design = &*design;
        fo.whole_layout = q.whole_layout;
        r.rules = q.overrides(rules_for_mask(*q.mask, q.vendor, design->grid_nm));
        r.spacing =
            spacing_rule_text(q.mask->pattern.min_spacing_cells, design->pitch_nm, design->grid_nm);
    } else {
        DrcRules rules;
        rules.min_gap_nm = q.vendor.min_gap_nm;
        rules.min_feature_nm = q.vendor.min_feature_nm;
        rules.max_vertices = q.vendor.max_vertices;
        r.rules = q.overrides(rules);
        fo.outline = q.outline;
    }
    fo.rules = r.rules;
    check_time_limit("check stopped before the design-rule check of " + q.input);
    r.check = check_file_geometry(file, fo);
    if (q.mask) add_pattern_spacing(r.check.drc, *q.mask, design->pitch_nm, r.rules);
    r.check.identity = check_film_identity(file, *readable_format_of(q.input), q.film);
    if (auto it = file.info.find("unit_assumed"); it != file.info.end()) {
        r.unit_assumed =
            "the file states no unit ($INSUNITS 0 or absent, no pinmask units= comment): read as " +
            it->second;
    }
    return r;
}

}  // namespace pinmask
