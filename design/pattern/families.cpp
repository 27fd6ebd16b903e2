#include "design/pattern/families.hpp"

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "design/pattern/random_sparse.hpp"

namespace pinmask {

Family parse_family(std::string_view name) {
    if (name == "random") return Family::kRandom;
    if (name == "paper") return Family::kPaper;
    if (name == "mura") return Family::kMura;
    if (name == "ura") {
        throw invalid_field(field_ref("family"), "ura",
                            "not available: a URA is rectangular (p x (p + 2) cells) and pinmask "
                            "patterns are square n x n tori; use mura (square, prime p = 4m + 1)");
    }
    throw invalid_field(field_ref("family"), std::string(name),
                        "must be one of random, paper, mura");
}

std::string family_name(Family family) {
    switch (family) {
        case Family::kRandom:
            return "random";
        case Family::kPaper:
            return "paper";
        case Family::kMura:
            return "mura";
    }
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
