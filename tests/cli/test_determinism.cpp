// Determinism end to end: the same command with the same seed and inputs, run twice in two fresh
// folders (same relative file names), writes byte-identical files: generate, psf, simulate,
// export (every format), search with --evals, decode. Search's run-log.csv (by evaluation
// count) and summary.md are byte-identical; its timing.csv (wall clock) by its final totals.
// search with a different --threads runs a different number of chains, so its results differ by
// design (same seed, inputs and thread count give identical results).
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "io/mask_json.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// Runs `pinmask ARGS` with `dir` as the working directory; returns the exit code.
int run_in(const TempDir& dir, const std::string& args) {
    const std::string cmd = "cd '" + dir.path.string() + "' && " + PINMASK_EXE + " " + args +
                            " >stdout.txt 2>stderr.txt </dev/null";
    const int status = std::system(cmd.c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code != 0) MESSAGE("pinmask " << args << ": " << slurp(dir.path / "stderr.txt"));
    return code;
}

// Every regular file under root (relative path -> bytes), without the captured stdout/stderr.
std::map<std::string, std::string> files_under(const fs::path& root) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        if (!e.is_regular_file()) continue;
        const std::string rel = fs::relative(e.path(), root).string();
        if (rel == "stdout.txt" || rel == "stderr.txt") continue;
        files[rel] = slurp(e.path());
    }
    return files;
}

// The last row (the final totals) without its first column (seconds). The rows before it are
// sampled by wall-clock time while the chains run, so their number and counts vary.
std::string final_totals(const std::string& csv) {
    std::istringstream in(csv);
    std::string line, last;
    while (std::getline(in, line)) {
        if (!line.empty()) last = line;
    }
    return last.substr(last.find(',') + 1);
}

// Both folders hold the same files with the same bytes (after `normalise` for named files).
void check_identical(
    const TempDir& a, const TempDir& b,
    const std::map<std::string, std::string (*)(const std::string&)>& normalise = {}) {
    const auto fa = files_under(a.path), fb = files_under(b.path);
    REQUIRE(fa.size() == fb.size());
    CHECK(fa.size() > 0);
    for (const auto& entry : fa) {
        const std::string& name = entry.first;
        const std::string& bytes = entry.second;
        INFO(name);
        REQUIRE(fb.count(name) == 1);
        const std::string base = fs::path(name).filename().string();
        if (const auto it = normalise.find(base); it != normalise.end()) {
            CHECK(it->second(bytes) == it->second(fb.at(name)));
        } else {
            CHECK(bytes == fb.at(name));
        }
    }
}

// Runs the same commands in two fresh folders (each seeded with the test mask) and compares.
struct Twin {
    TempDir a{"determinism-a"}, b{"determinism-b"};
    Twin() {
        for (const TempDir* d : {&a, &b}) {
            REQUIRE(run_in(*d,
                           "generate --grid 16 --holes 12 --seed 5 --pixels-per-cell 4 -o "
                           "m.mask.json") == 0);
        }
    }
    void run(const std::string& args) {
        REQUIRE(run_in(a, args) == 0);
        REQUIRE(run_in(b, args) == 0);
    }
};

}  // namespace

TEST_CASE("generate twice: byte-identical mask files (random, paper, mura)") {
    Twin t;
    t.run("generate --family paper --seed 9 -o paper.mask.json");
    t.run("generate --family mura --grid 13 --allow-violations -o mura.mask.json");
    check_identical(t.a, t.b);
}

TEST_CASE("psf twice: byte-identical TIFF, npy and sidecar") {
    Twin t;
    t.run("psf m.mask.json -o psf.tiff --npy");
    check_identical(t.a, t.b);
}

TEST_CASE("simulate twice: byte-identical captures, dark frames and configs") {
    Twin t;
    t.run("simulate m.mask.json --scene natural --snr 25 --seed 3 -o gauss.tiff");
    t.run(
        "simulate m.mask.json --scene usaf --photons 200 --read-noise 2 --dark-current 5 "
        "--optical-density 2 --full-sensor --sensor 100x90 --dark-frame dark.npy --seed 4 "
        "-o photon.npy");
    check_identical(t.a, t.b);
}

TEST_CASE("export twice: every format byte-identical (svg pdf gds dxf gerber png psf sidecar)") {
    Twin t;
    t.run("export m.mask.json -o out --npy --marks --label --frame 200um --dpi 600");
    t.run("export m.mask.json -o dark --tone dark --mirror --format svg,gds,dxf,gerber,pdf");
    check_identical(t.a, t.b);
}

TEST_CASE("decode twice: byte-identical images and configs") {
    Twin t;
    t.run("simulate m.mask.json --scene letter-R --snr 30 -o cap.tiff");
    t.run("decode cap.tiff --mask m.mask.json -o wiener.tiff");
    t.run("decode cap.tiff --mask m.mask.json --method tv --iters 30 -o tv.png");
    t.run("psf m.mask.json -o m.psf.tiff");
    t.run("decode cap.tiff --psf m.psf.tiff --method richardson-lucy --iters 20 -o from_psf.npy");
    check_identical(t.a, t.b);
}

TEST_CASE("search --evals twice with the same --threads: identical masks, config and log") {
    Twin t;
    const std::string common =
        "search --grid 16 --holes 12 --pixels-per-cell 4 --tiles 1 --evals 150 --prior-scenes 2 "
        "--top 3 --seed 11 --rerank-scenes letter-R --no-rerank-tv";
    t.run(common + " --threads 2 -o run2");
    t.run(common + " --threads 1 -o run1");
    // run-log.csv (by evaluation count) and summary.md are byte-identical; only
    // timing.csv (wall clock) is excluded from the claim.
    check_identical(t.a, t.b, {{"timing.csv", final_totals}});
    // By design a different thread count runs a different number of chains (150 evaluations
    // each), so the runs are different searches: the log counts 2 x 150 against 1 x 150.
    const std::string log2 = slurp(t.a.path / "run2" / "run-log.csv");
    const std::string log1 = slurp(t.a.path / "run1" / "run-log.csv");
    CHECK(log2.find(",300,") != std::string::npos);
    CHECK(log1.find(",150,") != std::string::npos);
    CHECK(log1.find(",300,") == std::string::npos);
    // Every written candidate is a valid mask file.
    for (const char* run : {"run1", "run2"}) {
        CHECK_NOTHROW(pinmask::io::read_mask_file(t.a.path / run / "rank-1.mask.json"));
    }
}
