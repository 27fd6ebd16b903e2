#include "cli/outputs/check_report.hpp"

#include <cmath>
#include <iostream>
#include <sstream>

#include "cli/options/flag_names.hpp"
#include "export/layout/geometry.hpp"

namespace pinmask::cli {
namespace {

std::string um_text(double nm) {
    if (std::isinf(nm)) return "none below the limit";
    std::ostringstream s;
    s << nm * 1e-3 << " um";
    return s.str();
}

}  // namespace

void print_check_text(const io::CheckReport& rep) {
    const VendorRules& vendor = rep.vendor;
    const FileCheck& c = rep.check;
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
    if (!rep.note.empty()) s << "  note        " << spell_flags(rep.note) << "\n";
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
