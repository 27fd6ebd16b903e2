// A write that fails part-way (a file-size limit, a full disk, a quota) ends the run cleanly:
// under `ulimit -f` every command that writes exits 1 naming the file and the reason, and
// leaves no file at all (no final name, no *.tmp-* temporary), where it used to die of SIGXFSZ
// mid-write and leave its temporaries. The limit goes through the same write() failure (EFBIG)
// as ENOSPC and EDQUOT; a file-size limit is the one a test can set without a full disk.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/cli_run.hpp"

using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = PINMASK_SOURCE_DIR;
const std::string kMask = (kSource / "fuzz/corpus/mask_json/small.mask.json").string();
const std::string kCapture = (kSource / "fuzz/corpus/image/cap.npy").string();

struct Run {
    int exit_code = -1;
    std::string err;
};

// Runs pinmask in `dir` under a file-size limit of `kib` KiB (bash's `ulimit -f`, 1024-byte
// blocks). Its stderr goes through a pipe (the limit applies to regular files only, so the
// message survives a limit of 0); stdout is dropped.
Run run_limited(const std::string& args, const fs::path& dir, int kib, const TempDir& logs) {
    const std::string script = "( ulimit -f " + std::to_string(kib) + " && exec " + PINMASK_EXE +
                               " " + args + " ) 2>&1 >/dev/null </dev/null | cat >'" +
                               (logs / "err") + "'; exit \\${PIPESTATUS[0]}";
    const std::string cmd = "cd '" + dir.string() + "' && bash -c \"" + script + "\"";
    const int status = std::system(cmd.c_str());
    Run r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = slurp(logs.path / "err");
    return r;
}

// Every regular file under `dir` (the inputs excepted), recursively.
std::vector<std::string> files_under(const fs::path& dir, const std::vector<std::string>& inputs) {
    std::vector<std::string> found;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        const std::string name = fs::relative(e.path(), dir).string();
        if (e.is_regular_file() && std::find(inputs.begin(), inputs.end(), name) == inputs.end())
            found.push_back(name);
    }
    return found;
}

struct Case {
    std::string writer;  // what the command writes
    std::string args;
    int kib;           // the limit: below the size of the file named in `path`
    std::string path;  // the file the message must name (relative to the run's folder)
};

}  // namespace

TEST_CASE("under a file-size limit every writer exits 1 naming the file and leaves no file") {
    TempDir d("fsize");
    TempDir logs("fsize-logs");
    std::ofstream(d / "sweep.json") << R"({"format": "pinmask-sweep", "version": 1,
  "base": {"grid": 8, "tiles": 1, "pixels_per_cell": 4, "evaluations_per_chain": 20,
           "top": 1, "rerank_scenes": [], "prior": {"family": "natural", "scenes": 2}},
  "grid": {"holes": [3]}})";
    const std::vector<std::string> inputs = {"sweep.json"};
    const std::string search =
        "search --grid 8 --holes 5 --tiles 1 --pixels-per-cell 4 "
        "--prior-scenes 2 --threads 1 --no-rerank --quiet ";
    const std::vector<Case> cases = {
        {"generate", "generate --grid 64 --holes 400 -o g.mask.json", 1, "g.mask.json"},
        {"psf", "psf " + kMask + " -o p.tiff", 1, "p.tiff"},
        {"simulate", "simulate " + kMask + " -o s.tiff", 1, "s.tiff"},
        {"decode", "decode " + kCapture + " --mask " + kMask + " -o d.tiff", 1, "d.tiff"},
        {"decode --stats", "decode " + kCapture + " --mask " + kMask + " -o d.png --stats d.json",
         1, "d."},
        {"depthmap",
         "depthmap " + kCapture + " --mask " + kMask + " --from 1m --to 2m --window 5 -o dm", 1,
         "dm/"},
        {"depth", "depth " + kMask + " --from 1m --to 2m -o dp", 1, "dp/"},
        {"export", "export " + kMask + " -o e", 8, "e/"},
        {"compare --report", "compare " + kMask + " --report r.pdf", 8, "r.pdf"},
        {"design --save-camera", "design --save-camera cam.json", 0, "cam.json"},
        {"sweep", "sweep sweep.json --quiet -o sw", 1, "sw/"},
        {"search", search + "--evals 20 -o se", 1, "se/"},
        {"search --checkpoint",
         search + "--evals 3000 --strategy random --checkpoint ck.json --checkpoint-every 1000 "
                  "-o sc",
         1, "ck.json"},
    };
    for (const Case& c : cases) {
        INFO(c.writer << ": pinmask " << c.args << " (ulimit -f " << c.kib << ")");
        const Run r = run_limited(c.args, d.path, c.kib, logs);
        INFO("stderr: " << r.err);
        CHECK(r.exit_code == 1);
        CHECK(r.err.find("could not write '") != std::string::npos);
        CHECK(r.err.find(c.path) != std::string::npos);
        CHECK(r.err.find("File too large") != std::string::npos);
        CHECK(r.err.find(".tmp-") == std::string::npos);
        const std::vector<std::string> left = files_under(d.path, inputs);
        std::string names;
        for (const std::string& n : left) names += n + " ";
        CHECK_MESSAGE(left.empty(), "left behind: " << names);
        for (const auto& e : fs::directory_iterator(d.path))
            if (e.path().filename() != "sweep.json") fs::remove_all(e.path());
    }
}
