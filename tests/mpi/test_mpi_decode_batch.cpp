// `pinmask decode --batch` under mpirun on localhost: 1, 2 and 3 ranks (3
// oversubscribed) write the same bytes as the plain run, every file including the summary (each
// run in its own folder with the same relative paths); a bad capture on one rank leaves no file
// on any rank and exits 2.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

int sh(const std::string& cmd) {
    const int status = std::system((cmd + " >/dev/null 2>&1 </dev/null").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::pair<std::string, std::string>> outputs(const fs::path& dir) {
    std::vector<std::pair<std::string, std::string>> files;
    for (const auto& e : fs::directory_iterator(dir))
        files.emplace_back(e.path().filename().string(), slurp(e.path()));
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

TEST_CASE("decode --batch under mpirun: the plain run's bytes on 1, 2 and 3 ranks") {
    TempDir dir("mpi-decode-batch");
    const fs::path d = dir.path;
    REQUIRE(run_cli("generate --grid 8 --holes 6 --tiles 2 --pixels-per-cell 4 --seed 3 -o " +
                    dir / "m.mask.json")
                .exit_code == 0);
    fs::create_directory(d / "caps");
    for (int s = 1; s <= 3; ++s)
        REQUIRE(run_cli("simulate " + dir / "m.mask.json" + " --scene letter-R --snr 30 --seed " +
                        std::to_string(s) + " -o " + dir / ("caps/c" + std::to_string(s) + ".tiff"))
                    .exit_code == 0);
    const std::string args =
        " decode --batch ../caps --mask ../m.mask.json --nsr 1e-3 "
        "--batch-stats --batch-format png -o out";
    auto run_in = [&](const std::string& name, const std::string& launcher) {
        fs::create_directories(d / name / "out");
        return sh("cd " + (d / name).string() + " && " + launcher + args);
    };
    REQUIRE(run_in("plain", PINMASK_EXE) == 0);
    auto strip_stats = [](std::vector<std::pair<std::string, std::string>> files) {
        // *.stats.json hold wall-clock timings: compared for presence only.
        for (auto& f : files)
            if (f.first.find(".stats.json") != std::string::npos) f.second.clear();
        return files;
    };
    const auto plain = strip_stats(outputs(d / "plain/out"));
    REQUIRE(plain.size() == 3 * 3 + 1);
    for (int ranks : {1, 2, 3}) {
        const std::string name = "ranks" + std::to_string(ranks);
        const std::string mpirun = std::string(PINMASK_MPIEXEC) + " -n " + std::to_string(ranks) +
                                   " --oversubscribe " + PINMASK_EXE;
        INFO(ranks, " ranks");
        REQUIRE(run_in(name, mpirun) == 0);
        const auto got = strip_stats(outputs(d / name / "out"));
        CHECK(got == plain);
    }
    // A spent time budget (1 us): each rank decodes its first capture (c1 on rank 0, c2 on
    // rank 1) and stops; c3 (rank 0's second) is not done; mpirun's exit code is 3, the ranks'.
    {
        const std::string mpirun2 =
            std::string(PINMASK_MPIEXEC) + " -n 2 --oversubscribe " + PINMASK_EXE;
        CHECK(run_in("spent", "PINMASK_TIME_LIMIT=1e-6 " + mpirun2) == 3);
        const auto got = strip_stats(outputs(d / "spent/out"));
        std::vector<std::pair<std::string, std::string>> want;
        for (const auto& f : plain)
            if (f.first.rfind("c3.", 0) != 0 && f.first != "batch-summary.json") want.push_back(f);
        auto without_summary = got;
        std::erase_if(without_summary,
                      [](const auto& f) { return f.first == "batch-summary.json"; });
        CHECK(without_summary == want);
        const std::string summary = slurp(d / "spent/out/batch-summary.json");
        CHECK(summary.find("\"not_done\": 1") != std::string::npos);
        CHECK(summary.find("\"done\": 2") != std::string::npos);
    }
    // A capture no rank can read (the second of three, rank 1's on 2 ranks): exit 2, no file.
    std::ofstream(d / "caps/c2.tiff") << "not a tiff";
    const std::string mpirun2 =
        std::string(PINMASK_MPIEXEC) + " -n 2 --oversubscribe " + PINMASK_EXE;
    CHECK(run_in("bad", mpirun2) == 2);
    CHECK(fs::is_empty(d / "bad/out"));
    CHECK(run_in("bad-plain", PINMASK_EXE) == 2);
    CHECK(fs::is_empty(d / "bad-plain/out"));
}
