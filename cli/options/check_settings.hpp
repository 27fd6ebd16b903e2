// `pinmask check`'s flags: their checks and the rule overrides they give (io/check_files runs
// the check).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "export/layout/geometry.hpp"
#include "export/pipeline/drc.hpp"
#include "io/sidecar_layout.hpp"

namespace pinmask::cli {

struct CheckOptions {
    std::string input;
    std::string mask;                   // design of a fabrication file
    std::optional<std::string> vendor;  // not given: the export sidecar's rules, else film
    std::optional<std::string> min_gap, min_feature, min_spacing;
    std::optional<std::size_t> max_vertices;
    std::size_t list = 20;
    double max_xor_um2 = 0.0;
    // Layout options of the design the file is compared with (as given to `pinmask export`).
    io::CheckLayoutText layout;
    bool no_sidecar = false;
    bool json = false;
};

// The input and the flags checked before any file is read: the input an existing regular file
// (not a device or a folder), --max-xor-um2 finite and >= 0, --list >= 1; InvalidInput naming
// each otherwise.
void validate(const CheckOptions& o);

// The rules: `rules` (the vendor's or the mask's) with every explicit flag applied.
DrcRules resolve_rules(const CheckOptions& o, DrcRules rules);

}  // namespace pinmask::cli
