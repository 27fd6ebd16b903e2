// The drawing unit of a fabrication file (`--units um|mm|in`): what one coordinate unit of a DXF
// drawing or one user unit of a GDSII/OASIS library means. Lengths inside pinmask stay integer
// nanometres (export/layout/layout.hpp); a unit is the whole number of nanometres in one drawing
// unit (1 in = 25.4 mm exactly), so every conversion is integer arithmetic.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace pinmask {

enum class FabUnit { kMicrometre, kMillimetre, kInch };

// "um", "mm" or "in"; anything else throws InvalidInput naming `field`.
FabUnit parse_fab_unit(std::string_view text, std::string_view field);
// "um", "mm", "in".
std::string fab_unit_name(FabUnit unit);
// "micrometres", "millimetres", "inches".
std::string fab_unit_words(FabUnit unit);
// Nanometres per drawing unit: 1000, 1000000, 25400000.
std::int64_t nm_per_unit(FabUnit unit);
// The DXF $INSUNITS code: 13 (microns), 4 (millimetres), 1 (inches).
int dxf_insunits(FabUnit unit);

}  // namespace pinmask
