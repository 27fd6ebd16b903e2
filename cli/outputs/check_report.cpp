#include "cli/outputs/check_report.hpp"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "export/layout/geometry.hpp"

namespace pinmask::cli {
namespace {

std::string um_text(double nm) {
    if (std::isinf(nm)) return "none below the limit";
    std::ostringstream s;
    s << nm * 1e-3 << " um";
    return s.str();
}

nlohmann::ordered_json finite_or_null(double nm) {
    return std::isfinite(nm) ? nlohmann::ordered_json(nm * 1e-3) : nlohmann::ordered_json();
}

nlohmann::ordered_json index_or_null(std::size_t i) {
    return i == kNoPolygon ? nlohmann::ordered_json() : nlohmann::ordered_json(i);
}

}  // namespace

void print_check_json(const CheckReport& rep) {
    const FileCheck& c = *rep.check;
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
        {"design_rules_checked", rep.vendor != "none"},
        {"input", rep.input},
        {"kind", rep.kind},
        {"vendor", rep.vendor},
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
    std::cout << j.dump() << "\n";
}

void print_check_text(const CheckReport& rep, const VendorRules& vendor) {
    const FileCheck& c = *rep.check;
    const DrcReport& r = c.drc;
    const bool clean = c.clean();
    std::ostringstream s;
    const DrcRules& ru = rep.rules;
    s << "check " << rep.input << " (" << rep.kind << "; vendor " << vendor.name << ": "
      << vendor.description << (rep.rules_source.empty() ? "" : "; rules: " + rep.rules_source)
      << ")\n";
    s << "  polygons    " << c.layout.polygons.size() << " + " << c.layout.annotations.size()
      << " annotations, tone " << tone_name(c.layout.tone) << "\n";
    const bool spacing = ru.min_center_spacing_nm > 0;
    s << "  rules       centre spacing "
      << (spacing ? ">= " + um_text(ru.min_center_spacing_nm) : "not checked")
      << ", gap >= " << um_text(double(ru.min_gap_nm))
      << ", feature >= " << um_text(double(ru.min_feature_nm)) << ", <= " << ru.max_vertices
      << " vertices\n";
    s << "  measured    centre spacing "
      << (spacing ? um_text(r.measured.min_center_spacing_nm) : "not checked") << ", gap "
      << um_text(r.measured.min_gap_nm) << ", feature " << um_text(r.measured.min_feature_nm)
      << "\n";
    if (!rep.spacing.empty()) s << "  spacing     " << rep.spacing << "\n";
    if (!rep.settings.empty()) s << "  settings    " << rep.settings << "\n";
    if (c.comparison) {
        const ReadBack& k = *c.comparison;
        const bool ok = k.xor_area_nm2 <= c.max_xor_nm2 && (k.file_hash.empty() || k.hash_ok());
        s << "  vs design   " << rep.mask << ": " << k.describe() << " (max XOR "
          << c.max_xor_nm2 * 1e-6 << " um^2)" << (ok ? "" : "  MISMATCH") << "\n";
    }
    if (c.picture)
        s << "  vs design   " << rep.mask << ": " << c.picture->method << ": " << c.picture->result
          << (c.picture->ok ? "" : "  MISMATCH") << "\n";
    for (const FilmIdentityItem& i : c.identity.items)
        s << "  film        " << i.what << ": " << i.message << (i.ok ? "" : "  MISMATCH") << "\n";
    if (!rep.note.empty()) s << "  note        " << rep.note << "\n";
    if (r.clean()) {
        s << "  violations  none\n";
    } else {
        std::size_t total = 0;
        std::string parts;
        for (const auto& [rule, n] : r.counts) {
            total += n;
            parts += (parts.empty() ? "" : ", ") + rule + " " + std::to_string(n);
        }
        s << "  violations  " << total << " (" << parts << ")"
          << (r.truncated ? ", scan stopped early" : "") << "; at most " << rep.list
          << " listed per rule\n";
        for (const DrcViolation& v : r.violations) {
            s << "    " << drc_rule_name(v.rule) << ": " << v.message << "\n";
        }
    }
    // Vendor "none" has no process limits: a clean result there checked geometry only, and
    // says so rather than "clean".
    if (clean && vendor.name == "none")
        s << "  result      no design rules given: none checked (geometry only: "
          << (spacing ? "centre spacing, " : "") << "no touching polygons); give --vendor\n";
    else
        s << "  result      " << (clean ? "clean" : "FAILED") << "\n";
    std::cout << s.str();
}

}  // namespace pinmask::cli
