#include "io/check_json.hpp"

#include <cmath>

#include "export/layout/geometry.hpp"

namespace pinmask::io {
namespace {

nlohmann::ordered_json finite_or_null(double nm) {
    return std::isfinite(nm) ? nlohmann::ordered_json(nm * 1e-3) : nlohmann::ordered_json();
}

nlohmann::ordered_json index_or_null(std::size_t i) {
    return i == kNoPolygon ? nlohmann::ordered_json() : nlohmann::ordered_json(i);
}

}  // namespace

nlohmann::ordered_json check_json(const CheckReport& rep) {
    const FileCheck& c = rep.check;
    const DrcReport& r = c.drc;
    const bool clean = c.clean();
    nlohmann::ordered_json v = nlohmann::ordered_json::array();
    for (const DrcViolation& x : r.violations) {
        v.push_back({{"rule", drc_rule_name(x.rule)},
                     {"message", x.message},
                     {"x_um", double(x.where.x) * 1e-3},
                     {"y_um", double(x.where.y) * 1e-3},
                     {"polygon_a", index_or_null(x.polygon_a)},
                     {"polygon_b", index_or_null(x.polygon_b)},
                     {"value", x.value},
                     {"limit", x.limit},
                     {"unit", drc_rule_unit(x.rule)}});
    }
    nlohmann::ordered_json j = {
        {"clean", clean},
        {"design_rules_checked", rep.vendor.name != "none"},
        {"input", rep.input},
        {"kind", rep.kind},
        {"vendor", rep.vendor.name},
        {"rules_from", rep.rules_source},
        {"settings", rep.settings},
        {"tone", tone_name(c.layout.tone)},
        {"polygons", c.layout.polygons.size()},
        {"annotations", c.layout.annotations.size()},
        {"rules",
         {{"min_center_spacing_um", rep.rules.min_center_spacing_nm * 1e-3},
          {"min_gap_um", double(rep.rules.min_gap_nm) * 1e-3},
          {"min_feature_um", double(rep.rules.min_feature_nm) * 1e-3},
          {"max_vertices", rep.rules.max_vertices}}},
        {"measured",
         {{"min_center_spacing_um", finite_or_null(r.measured.min_center_spacing_nm)},
          {"min_gap_um", finite_or_null(r.measured.min_gap_nm)},
          {"min_feature_um", finite_or_null(r.measured.min_feature_nm)}}},
        {"counts", r.counts},
        {"truncated", r.truncated},
        {"violations", v}};
    if (c.comparison) {
        const ReadBack& k = *c.comparison;
        j["comparison"] = {
            {"mask", rep.mask},
            {"xor_area_um2", k.xor_area_nm2 * 1e-6},
            {"max_xor_area_um2", c.max_xor_nm2 * 1e-6},
            {"file_hash", k.file_hash},
            {"mask_hash", k.design_hash},
            {"rings_only_in_file", k.only_file},
            {"rings_only_in_design", k.only_design},
            {"ok", k.xor_area_nm2 <= c.max_xor_nm2 && (k.file_hash.empty() || k.hash_ok())}};
    }
    if (!c.identity.items.empty()) {
        nlohmann::ordered_json items = nlohmann::ordered_json::array();
        for (const FilmIdentityItem& i : c.identity.items)
            items.push_back({{"what", i.what},
                             {"found", i.found},
                             {"expected", i.expected.empty() ? nlohmann::ordered_json()
                                                             : nlohmann::ordered_json(i.expected)},
                             {"source", i.source},
                             {"ok", i.ok},
                             {"message", i.message}});
        j["film_identity"] = {{"ok", c.identity.ok()}, {"items", items}};
    }
    if (c.picture)
        j["picture"] = {
            {"method", c.picture->method}, {"result", c.picture->result}, {"ok", c.picture->ok}};
    return j;
}

}  // namespace pinmask::io
