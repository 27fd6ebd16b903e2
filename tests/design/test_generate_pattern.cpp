// design/pattern/generate_pattern against the family generators called directly, and its rules.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "core/errors/error.hpp"
#include "design/pattern/exclusion_grid.hpp"
#include "design/pattern/generate_pattern.hpp"
#include "design/pattern/mura.hpp"
#include "design/pattern/random_sparse.hpp"

using namespace pinmask;

namespace {

std::string message_of(const GeneratePatternOptions& o) {
    try {
        generate_pattern(o);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST_CASE("generate_pattern: each family equals its generator with the same seed") {
    GeneratePatternOptions o;
    o.seed = 7;
    o.grid = 20;
    o.holes = 25;
    o.tiles = 3;
    o.spacing = 1.5;
    const GeneratedPattern g = generate_pattern(o);
    RandomSparseOptions r;
    r.n = 20;
    r.holes = 25;
    r.min_spacing_cells = 1.5;
    r.tiles_rows = r.tiles_cols = 3;
    std::mt19937_64 rng(7);
    const Pattern ref = random_sparse_pattern(r, rng);
    CHECK(g.pattern.pinholes == ref.pinholes);
    CHECK(g.spacing_violations == 0);

    o = {};
    o.family = Family::kPaper;
    o.seed = 3;
    std::mt19937_64 rng3(3);
    CHECK(generate_pattern(o).pattern.pinholes == paper_pattern(rng3).pinholes);

    o = {};
    o.family = Family::kMura;
    o.grid = 13;
    o.allow_violations = true;
    const GeneratedPattern mura = generate_pattern(o);
    CHECK(mura.pattern.pinholes == mura_pattern(13, 2.0, 2, 2).pinholes);
    CHECK(mura.spacing_violations == count_spacing_violations(mura.pattern));
    CHECK(mura.spacing_violations > 0);
}

TEST_CASE("generate_pattern: refusals name the field, the value and the rule") {
    GeneratePatternOptions o;
    o.family = Family::kPaper;
    o.grid = 20;
    CHECK(message_of(o) == "no error");  // not given: the family's own geometry
    o.grid_given = true;
    CHECK(message_of(o).find("`grid` = 20: the paper family fixes n = 16") != std::string::npos);

    o = {};
    o.family = Family::kMura;
    o.grid = 13;
    CHECK(message_of(o).find("`spacing` = 2: ") != std::string::npos);
    CHECK(message_of(o).find("pass `allow_violations` to write it anyway") != std::string::npos);
    o.spacing = 1.0;
    o.holes = 5;
    o.holes_given = true;
    CHECK(message_of(o).find("`holes` = 5: a MURA of order 13 has") != std::string::npos);

    o = {};
    o.attempts = 0;
    CHECK(message_of(o).find("`attempts` = 0: must be >= 1") != std::string::npos);
    o = {};
    o.tiles = 0;
    CHECK(message_of(o).find("`tiles` = 0") != std::string::npos);
    o = {};
    o.grid = kMaxGrid + 1;
    CHECK(message_of(o).find("`grid` = ") != std::string::npos);

    CHECK_NOTHROW(check_period_psf_size(724, 16, true));
    CHECK_THROWS_WITH_AS(check_period_psf_size(725, 16, true),
                         doctest::Contains("`pixels_per_cell` = 725"), InvalidInput);
}
