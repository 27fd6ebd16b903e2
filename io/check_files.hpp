// The check transaction over files, for both faces (`pinmask check` and Python's check()): the
// export sidecar beside a fabrication file (its rules and layout settings), the vendor's rules,
// the design mask (given, or the one the sidecar names), then export/pipeline/check_run's check
// of a mask, of a fabrication file read back, or of a picture (PDF, PNG, 1-bit TIFF) against its
// design. io/check_json renders the report as `check --json` prints it and check() returns it.
// The faces check their own arguments first (the input an existing file, the ranges) and give
// their rule overrides; between stages the time budget (core/limits) is polled.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "design/pattern/mask.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/pipeline/check_run.hpp"
#include "export/pipeline/drc.hpp"
#include "export/pipeline/file_check.hpp"
#include "io/sidecar_layout.hpp"

namespace pinmask::io {

struct CheckRequest {
    std::string input;                  // the file checked, or the name of `input_mask`
    const Mask* input_mask = nullptr;   // a mask given as a value instead of a file
    std::string mask;                   // the design of a fabrication file: its path ("" none)
    const Mask* mask_value = nullptr;   // ... or the design as a value, named by `mask`
    std::optional<std::string> vendor;  // not given: the export sidecar's rules, else film
    RuleOverrides overrides;            // the face's rule overrides (identity when not given)
    bool spacing_given = false;  // the centre spacing overridden: its rule in words not reported
    double max_xor_um2 = 0.0;
    CheckLayoutText layout;  // the design's layout settings as given (must agree with a sidecar)
    bool no_sidecar = false;
    std::size_t list = 20;  // violations listed per rule
};

struct CheckReport {
    std::string input, kind;
    VendorRules vendor;        // the vendor's rules (before the mask and the overrides)
    std::string rules_source;  // where they came from: given, the export sidecar, default (film)
    std::string mask;          // the design compared with ("" if none)
    std::string settings;      // where the layout settings came from
    std::size_t list = 20;
    FileCheck check;
    DrcRules rules;       // the rules checked
    std::string spacing;  // the spacing rule in words (design/optics/fab_grid), "" without a mask
    std::string note;
    // A fabrication file that states no unit, read without a sidecar: how it was read ("" else).
    std::string unit_assumed;
};

CheckReport run_check(const CheckRequest& request);

}  // namespace pinmask::io
