#include "cli/options/check_settings.hpp"

#include <cmath>
#include <filesystem>
#include <string>

#include "core/errors/error.hpp"
#include "core/files/input_file.hpp"
#include "core/units/units.hpp"

namespace pinmask::cli {

namespace fs = std::filesystem;

void validate(const CheckOptions& o) {
    if (fs::exists(o.input)) {
        if (const auto problem = input_file_problem(o.input))
            throw invalid_field("input", o.input, *problem);
    }
    if (!fs::is_regular_file(o.input))
        throw invalid_field("input", o.input, "must be an existing mask or fabrication file");
    if (!std::isfinite(o.max_xor_um2) || o.max_xor_um2 < 0)
        throw invalid_field("--max-xor-um2", std::to_string(o.max_xor_um2),
                            "must be finite and >= 0");
    if (o.list < 1) throw invalid_field("--list", std::to_string(o.list), "must be >= 1");
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
    if (o.min_gap) rules.min_gap_nm = length_nm(*o.min_gap, "--min-space/--min-gap", 1);
    if (o.min_feature) rules.min_feature_nm = length_nm(*o.min_feature, "--min-feature", 0);
    if (o.min_spacing) {
        rules.min_center_spacing_nm = double(length_nm(*o.min_spacing, "--min-spacing", 0));
    }
    if (o.max_vertices) rules.max_vertices = *o.max_vertices;
    rules.max_reported_per_rule = o.list;
    return rules;
}

}  // namespace pinmask::cli
