#include "design/pattern/families.hpp"

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/errors/name_table.hpp"
#include "design/pattern/random_sparse.hpp"

namespace pinmask {

namespace {

constexpr NameTable<Family, 3> kFamilyNames{
    {{Family::kRandom, "random"}, {Family::kPaper, "paper"}, {Family::kMura, "mura"}}};

}  // namespace

Family parse_family(std::string_view name) {
    for (const auto& [family, spelled] : kFamilyNames)
        if (name == spelled) return family;
    if (name == "ura") {
        throw invalid_field(field_ref("family"), "ura",
                            "not available: a URA is rectangular (p x (p + 2) cells) and pinmask "
                            "patterns are square n x n tori; use mura (square, prime p = 4m + 1)");
    }
    throw invalid_field(field_ref("family"), std::string(name),
                        "must be one of " + names_of(kFamilyNames, ", "));
}

std::string family_name(Family family) {
    for (const auto& [value, spelled] : kFamilyNames)
        if (value == family) return spelled;
    return "random";
}

Pattern paper_pattern(std::mt19937_64& rng) {
    RandomSparseOptions o;
    o.n = kPaperGrid;
    o.holes = kPaperHoles;
    o.tiles_rows = kPaperTiles;
    o.tiles_cols = kPaperTiles;
    o.min_spacing_cells = kPaperSpacingCells;
    return random_sparse_pattern(o, rng);
}

}  // namespace pinmask
