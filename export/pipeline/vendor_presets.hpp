// Vendor presets for `pinmask export --vendor NAME` (listed by `--vendor list`): what a kind of
// shop asks for, as one small table. A preset sets formats, unit, tone, emulsion side, frame,
// vertex limit, grid, native circles, kerf and plate size, plus the design-rule preset
// (export/layout/vendor_rules) checked on the layout; explicit flags win over it. The design-rule
// names film, chrome and none remain valid --vendor values that set only the rules.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "export/formats/fab_units.hpp"
#include "export/formats/read_any.hpp"
#include "export/layout/layout.hpp"
#include "export/layout/vendor_rules.hpp"

namespace pinmask {

struct VendorPreset {
    std::string name;
    std::string description;  // one line: who it is for and why these values
    std::vector<FabFormat> formats;
    FabUnit unit = FabUnit::kMicrometre;
    Tone tone = Tone::kClear;
    bool emulsion_down = false;  // mirrored: right-reading through the base
    double frame_m = 0.0;
    std::size_t max_vertices = 199;
    double grid_m = 1e-9;
    bool native_circles = false;
    double kerf_m = 0.0;    // laser cutting: holes drawn this much smaller
    double plate_m = 0.0;   // the extent must fit a square of this side (0: no limit)
    double tiff_dpi = 0.0;  // plotter raster resolution (0: the default)
    std::string drc;        // design-rule preset (export/layout/vendor_rules)
};

// Every full preset, in listing order.
const std::vector<VendorPreset>& vendor_presets();

// The preset called `name`, or nullptr when `name` is a design-rule preset only (film, chrome,
// none). Anything else throws InvalidInput naming --vendor and listing every name.
const VendorPreset* find_vendor_preset(std::string_view name);

// The design rules of a vendor name: a full preset's rule preset (chrome-photomask -> chrome),
// or a rule preset itself (film, chrome, none); InvalidInput naming `vendor` otherwise.
VendorRules vendor_rules_for(std::string_view name);

// The rule lengths in words: "features >= 2.000 um, spaces >= 1.000 um, <= 199 vertices".
std::string vendor_rules_text(const VendorRules& rules);

// One line per preset and per design-rule preset, for `--vendor list`.
std::string vendor_list_text();

}  // namespace pinmask
