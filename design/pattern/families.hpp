// Pattern families by name, and the paper's geometry. The families themselves live in
// design/pattern/random_sparse.hpp (random, paper) and design/pattern/mura.hpp (mura).
#pragma once

#include <random>
#include <string>
#include <string_view>

#include "design/pattern/pattern.hpp"

namespace pinmask {

enum class Family { kRandom, kPaper, kMura };

// "random" | "paper" | "mura". "ura" and anything else throw InvalidInput naming `family`
// (a URA is p x (p + 2), not square, so it cannot be an n x n torus pattern).
Family parse_family(std::string_view name);
std::string family_name(Family family);

// The paper's basic pattern: 16 x 16 cells, 20 pinholes, 2 x 2 cyclic tiles, spacing 2 cells.
inline constexpr int kPaperGrid = 16;
inline constexpr int kPaperHoles = 20;
inline constexpr int kPaperTiles = 2;
inline constexpr double kPaperSpacingCells = 2.0;

// The paper's geometry with its 20 pinholes placed by random sequential choice (the paper's
// own placement is not published as coordinates, so this is the same family, not its mask).
Pattern paper_pattern(std::mt19937_64& rng);

}  // namespace pinmask
