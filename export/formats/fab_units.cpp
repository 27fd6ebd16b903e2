#include "export/formats/fab_units.hpp"

#include <array>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

// Everything a unit stands for, one row each: the only place a unit's facts are written.
struct FabUnitRow {
    FabUnit unit;
    const char* name;   // as --units spells it
    const char* words;  // in sentences
    std::int64_t nm;    // nanometres per drawing unit
    int insunits;       // the DXF $INSUNITS code
};
constexpr std::array<FabUnitRow, 3> kUnits{{
    {FabUnit::kMicrometre, "um", "micrometres", 1000, 13},
    {FabUnit::kMillimetre, "mm", "millimetres", 1000000, 4},
    {FabUnit::kInch, "in", "inches", 25400000, 1},
}};

// The unit's row; nullptr for a value no enumerator has.
const FabUnitRow* row_of(FabUnit unit) {
    for (const FabUnitRow& row : kUnits)
        if (row.unit == unit) return &row;
    return nullptr;
}

}  // namespace

FabUnit parse_fab_unit(std::string_view text, std::string_view field) {
    for (const FabUnitRow& row : kUnits)
        if (text == row.name) return row.unit;
    throw invalid_field(std::string(field), std::string(text), "must be one of um, mm, in");
}

std::string fab_unit_name(FabUnit unit) {
    const FabUnitRow* row = row_of(unit);
    return row ? row->name : "?";
}

std::string fab_unit_words(FabUnit unit) {
    const FabUnitRow* row = row_of(unit);
    return row ? row->words : "?";
}

std::int64_t nm_per_unit(FabUnit unit) {
    const FabUnitRow* row = row_of(unit);
    return row ? row->nm : 1;
}

int dxf_insunits(FabUnit unit) {
    const FabUnitRow* row = row_of(unit);
    return row ? row->insunits : 0;
}

}  // namespace pinmask
