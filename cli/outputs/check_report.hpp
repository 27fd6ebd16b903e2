// Rendering of `pinmask check` results: the text table and the --json object.
#pragma once

#include <string>

#include "export/layout/vendor_rules.hpp"
#include "export/pipeline/file_check.hpp"

namespace pinmask::cli {

struct CheckReport {
    std::string input, kind, vendor, mask;  // mask: the design compared with ("" if none)
    std::string settings;                   // where the layout settings came from
    std::size_t list = 20;                  // violations listed per rule
    const FileCheck* check = nullptr;
    DrcRules rules;
    std::string rules_source;  // where the vendor rules came from (--vendor, sidecar, default)
    std::string spacing;  // the spacing rule in words (design/optics/fab_grid), "" without a mask
    std::string note;
};

void print_check_text(const CheckReport& r, const VendorRules& vendor);
void print_check_json(const CheckReport& r);

}  // namespace pinmask::cli
