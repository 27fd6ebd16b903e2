// Input errors under mpirun (cli/main.cpp): every rank parses the same flags and reads the same
// files, so an input error is every rank's alike; rank 0 alone prints it, the other ranks wait
// until it has, and every rank exits 2. Each rank runs under `sh -c`, which prints the rank's
// exit code on stdout.
#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

#include "tests/support/cli_run.hpp"

using pinmask::test::slurp;
using pinmask::test::TempDir;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

struct RankRun {
    std::string out, err;
};

RankRun run_ranks(int ranks, const std::string& args, const TempDir& dir) {
    const std::string out = dir / "out.txt", err = dir / "err.txt";
    const std::string cmd = std::string(PINMASK_MPIEXEC) + " -n " + std::to_string(ranks) +
                            " --oversubscribe sh -c '\"$0\" \"$@\"; echo \"exit $?\"' " +
                            PINMASK_EXE + " " + args + " >" + out + " 2>" + err + " </dev/null";
    REQUIRE(std::system(cmd.c_str()) != -1);  // sh -c ends 0: the ranks' codes are on stdout
    RankRun r;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

}  // namespace

TEST_CASE("an input error under mpirun is printed once, by rank 0; every rank exits 2") {
    TempDir dir("mpi-errors");
    struct Case {
        const char* args;
        const char* message;
    };
    const Case cases[] = {
        // A flag CLI11 refuses while parsing.
        {"search --grid abc", "Could not convert: --grid = abc"},
        // An InvalidInput a command throws before any rank starts MPI.
        {"score /nonexistent/a.mask.json --metrics sidelobes", "pinmask: error:"},
        // A missing sweep file (sweep runs over MPI ranks once started).
        {"sweep /nonexistent/s.json -o out", "does not exist"},
    };
    for (const Case& c : cases) {
        for (int ranks : {2, 3}) {
            const std::string args = c.args;
            INFO(args, " on ", ranks, " ranks");
            const RankRun r = run_ranks(ranks, args, dir);
            INFO("stderr: ", r.err);
            CHECK(count(r.err, c.message) == 1);
            CHECK(count(r.out, "exit 2") == static_cast<std::size_t>(ranks));
            CHECK(count(r.out, "exit ") == static_cast<std::size_t>(ranks));
        }
    }
}
