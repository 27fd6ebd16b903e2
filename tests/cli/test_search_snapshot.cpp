// cli/outputs/search_snapshot: the best-so-far.mask.json that `pinmask search` keeps while it
// runs. Only the better of two offers is kept; the first best is written at once; later ones
// wait for the period, except right after the interrupt flag rises; the file is a whole mask
// file (read back with the mask reader); the end removes it, and a failed run (no finish())
// removes it and the folder it made. The test polls for files, never for a time.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "cli/outputs/search_snapshot.hpp"
#include "design/pattern/pattern.hpp"
#include "io/mask_json.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

Mask template_mask() {
    const fs::path source = PINMASK_SOURCE_DIR;
    Mask m = io::read_mask_file(source / "fuzz" / "corpus" / "mask_json" / "small.mask.json");
    m.provenance.family = "search:anneal";
    return m;
}

// `mask` with one pinhole moved: another pattern of the same grid and pinhole count.
Pattern variant(const Mask& m, int k) {
    Pattern p = m.pattern;
    Cell& c = p.pinholes.back();
    c = {c.row, (c.col + k) % p.n};
    return p;
}

// Polls (1 ms steps, at most 60 s) until `done` holds.
template <class F>
bool poll(F done) {
    for (int i = 0; i < 60000; ++i) {
        if (done()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return done();
}

}  // namespace

TEST_CASE("best-so-far snapshot: the best offered, at once on the signal, removed at the end") {
    TempDir dir("search-snapshot");
    const Mask tmpl = template_mask();
    const fs::path file = dir.path / "run" / cli::kBestSoFarName;  // "run" does not exist yet
    std::atomic<bool> interrupted{false};
    {
        cli::BestSoFarSnapshot snap(file, tmpl, &interrupted, 1e9);  // no second periodic write
        const Pattern a = variant(tmpl, 1), c = variant(tmpl, 3);
        snap.offer(a, -1.0);
        REQUIRE(poll([&] { return snap.writes() == 1; }));
        Mask back = io::read_mask_file(file);
        CHECK(back.pattern.pinholes == sorted_pinholes(a));
        CHECK(back.provenance.family == "search:anneal (best so far)");
        CHECK(back.provenance.scores.at("search_objective") == -1.0);
        CHECK(back.camera.pinhole_m == tmpl.camera.pinhole_m);
        snap.offer(variant(tmpl, 2), -0.5);  // worse: ignored
        snap.offer(c, -2.0);
        snap.offer(variant(tmpl, 4), -1.5);  // worse than c
        interrupted = true;                  // the first signal: written at once
        REQUIRE(poll([&] { return snap.writes() == 2; }));
        back = io::read_mask_file(file);
        CHECK(back.pattern.pinholes == sorted_pinholes(c));
        CHECK(back.provenance.scores.at("search_objective") == -2.0);
        snap.finish();  // the final files supersede it
        CHECK_FALSE(fs::exists(file));
        CHECK(fs::is_directory(dir.path / "run"));
    }
    // A run that fails after a snapshot (no finish()) leaves no file, nor the folder it made.
    const fs::path failed = dir.path / "failed" / cli::kBestSoFarName;
    {
        cli::BestSoFarSnapshot snap(failed, tmpl, nullptr);
        snap.offer(variant(tmpl, 1), -1.0);
        REQUIRE(poll([&] { return snap.writes() == 1; }));
        CHECK(fs::exists(failed));
    }
    CHECK_FALSE(fs::exists(dir.path / "failed"));
    for (const auto& e : fs::recursive_directory_iterator(dir.path))
        CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
}
