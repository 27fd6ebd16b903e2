// Reads GDSII streams like the ones pinmask writes (export/formats/gds_writer) and hierarchical
// ones (KLayout, Virtuoso): structures holding BOUNDARY elements (each XY closed: first point
// repeated), optionally TEXT elements, whose strings give the info tokens, and SREF / AREF
// references to other structures. The hierarchy is flattened into the rings of the one top
// structure (the one no other references): each reference placed by translation only (an SREF
// at its XY point; an AREF at every cols x rows step of its three XY points, steps whole
// database units), at most 16 levels deep and 10^8 placements, coordinates within 2^30 nm.
// Coordinates are converted to nanometres with the UNITS record (the database unit must be a
// whole number of nanometres). Strict and bounded: every record's length and data type are
// checked against the remaining bytes before use; PATH, BOX and NODE elements, references with
// reflection, magnification or rotation, references to undefined structures, cycles or more than
// one top structure, truncation, or anything after ENDLIB other than zero padding throw
// InvalidInput. Memory is checked against the process budget while flattening.
// info: "library", "structure" (the top one), "hierarchy" ("yes" when the file has more than one
// structure), "layers" ("1/0 2/0": layer/datatype pairs in first-use order), "db_unit_m", plus
// the TEXT tokens.
#pragma once

#include <string_view>

#include "export/layout/rings.hpp"

namespace pinmask {

FileGeometry read_gds(std::string_view bytes);

}  // namespace pinmask
