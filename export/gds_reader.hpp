// Reads GDSII streams like the ones pinmask writes (export/gds_writer): exactly one structure
// holding BOUNDARY elements (each XY closed: first point repeated) and optionally TEXT elements,
// whose strings give the info tokens. Coordinates are converted to nanometres with the UNITS
// record (the database unit must be a whole number of nanometres). Strict and bounded: every
// record's length and data type are checked against the remaining bytes before use; PATH,
// SREF, AREF, BOX and NODE elements, truncation, or anything after ENDLIB other than zero
// padding throw InvalidInput. Memory stays proportional to the input.
// info: "library", "structure", "layers" ("1/0 2/0": layer/datatype pairs in first-use order),
// "db_unit_m", plus the TEXT tokens.
#pragma once

#include <string_view>

#include "export/rings.hpp"

namespace pinmask {

FileGeometry read_gds(std::string_view bytes);

}  // namespace pinmask
