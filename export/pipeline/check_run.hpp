// The check, one call per kind of input (io/check_files runs them for both faces, `pinmask
// check` and Python's check()): a mask checked on the layout export builds from it
// (check_mask), and a fabrication file read back and checked against its design when one is
// known (check_fabrication: the design's layout, export/pipeline/file_check's comparison and
// design-rule check, the pattern's centre spacing, and what identifies the film,
// export/pipeline/film_identity). io/check_files reads the files, the export sidecar and the
// mask, and takes the layout settings and each face's rule overrides (their flags or keywords,
// refused in their own spelling). Between stages the time budget (core/limits) is polled,
// naming the input.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "design/pattern/mask.hpp"
#include "export/formats/read_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/pipeline/drc.hpp"
#include "export/pipeline/file_check.hpp"
#include "export/pipeline/film_identity.hpp"

namespace pinmask {

// The face's overrides applied to the vendor's or the mask's rules.
using RuleOverrides = std::function<DrcRules(DrcRules)>;

struct CheckRun {
    FileCheck check;
    DrcRules rules;       // the rules checked
    std::string spacing;  // the mask's spacing rule in words (design/optics/fab_grid); "" without
    // A fabrication file that states no unit (a DXF without $INSUNITS): the warning saying how it
    // was read; "" otherwise.
    std::string unit_assumed;
};

// The mask's layout (`layout`), the mask's rules under `vendor` with the overrides, the
// design-rule check and the pattern's centre spacing. `input` names the mask in the time-limit
// message.
CheckRun check_mask(const Mask& mask, const LayoutOptions& layout, const VendorRules& vendor,
                    const RuleOverrides& overrides, const std::string& input);

struct FabricationCheckRequest {
    std::string input;             // the file's path (its format; named in time-limit messages)
    const Mask* mask = nullptr;    // the design the file was exported from, when known
    LayoutOptions layout;          // the design's layout settings (with a mask)
    bool whole_layout = false;     // with a mask: the settings came from the export sidecar
    std::optional<BoxNm> outline;  // without a mask: where the pinholes are
    VendorRules vendor;
    RuleOverrides overrides;
    double max_xor_nm2 = 0.0;
    FilmIdentityExpected film;  // what the film should be (io/sidecar_identity)
};

// `file`, read from request.input, checked: with a mask, against the design's layout under the
// mask's rules; without, under the vendor's limits.
CheckRun check_fabrication(const FileGeometry& file, const FabricationCheckRequest& request);

}  // namespace pinmask
