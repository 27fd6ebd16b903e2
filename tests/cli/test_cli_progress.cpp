// Progress when stderr is not a terminal (a pipe here, as a batch job's log): plain lines, the
// set-up phases named, no bar redrawn in place, a last 100 % line (cli/outputs/progress).
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::TempDir;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// stderr of `pinmask args` through a pipe (stdout discarded).
std::string piped_stderr(const std::string& args, const TempDir& dir) {
    const std::string err = (dir.path / "stderr.txt").string();
    const std::string cmd =
        std::string(PINMASK_EXE) + " " + args + " 2>&1 >/dev/null </dev/null | cat > " + err;
    REQUIRE(std::system(cmd.c_str()) == 0);
    return pinmask::test::slurp(err);
}

}  // namespace

TEST_CASE("compare on a pipe: the set-up phase, each mask named, a last 100 % line") {
    TempDir dir("progress-compare");
    const std::string a = (dir.path / "a.mask.json").string(),
                      b = (dir.path / "b.mask.json").string();
    for (const auto& [path, seed] : {std::pair{a, 1}, std::pair{b, 2}}) {
        REQUIRE(run_cli("generate --grid 8 --holes 5 --pixels-per-cell 4 --seed " +
                        std::to_string(seed) + " -o " + path)
                    .exit_code == 0);
    }
    const std::string text =
        piped_stderr("compare " + a + " " + b + " --scenes letter-R --tv-iters 20", dir);
    INFO(text);
    CHECK(contains(text, "pinmask compare: building the scenes and the prior...\n"));
    CHECK(contains(text, "pinmask compare: mask 1/2: a.mask.json (metrics, simulated decodes)"));
    CHECK(contains(text, "pinmask compare: mask 2/2: b.mask.json"));
    CHECK(contains(text, "pinmask compare: 100% 2 masks compared\n"));
    CHECK_FALSE(contains(text, "\r"));
}

TEST_CASE("search on a pipe: set-up phases named before the chains, rate lines plain") {
    TempDir dir("progress-search");
    const std::string text = piped_stderr(
        "search --grid 8 --pixels-per-cell 4 --tiles 1 --holes 5 --prior-scenes 2 --threads 1 "
        "--top 1 --seed 3 --evals 200 --rerank-scenes letter-R -o " +
            (dir.path / "run").string(),
        dir);
    INFO(text);
    CHECK(contains(text, "pinmask search: building the kernel and the scene prior...\n"));
    CHECK(contains(text, "pinmask search: building the re-rank scenes...\n"));
    CHECK(contains(text, "pinmask search: starting the chains...\n"));
    CHECK(contains(text, "pinmask search: 100% rerank: re-ranked 1/1\n"));
    CHECK_FALSE(contains(text, "\r"));
}
