// Shared fixture of the CLI tests that score masks (test_cli_score.cpp, test_cli_robust.cpp): two
// small random masks written by `pinmask generate` (8 x 8 cells of 4 pixels, a 32 x 32 period, so
// simulated metrics stay fast), seeds 1 and 2, in a fresh temporary folder.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "tests/support/cli_run.hpp"

namespace pinmask::test {

struct GeneratedMasks {
    TempDir dir;
    std::string a, b;
    // `tag` names the temporary folder (pinmask-<tag>-...).
    explicit GeneratedMasks(const std::string& tag) : dir(tag) {
        a = dir / "a.mask.json";
        b = dir / "b.mask.json";
        const std::string common = " --family random --grid 8 --holes 5 --pixels-per-cell 4 ";
        REQUIRE(run_cli("generate" + common + "--seed 1 -o " + a).exit_code == 0);
        REQUIRE(run_cli("generate" + common + "--seed 2 -o " + b).exit_code == 0);
    }
};

}  // namespace pinmask::test
