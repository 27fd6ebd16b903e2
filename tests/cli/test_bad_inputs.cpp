// The malformed-input corpus (tests/bad-inputs/, manifest.txt) end to end: every line runs its
// pinmask command on its file and must exit with the expected code (2 unless the manifest says
// otherwise), print a message naming the problem, and leave nothing behind: the output folder
// stays empty (no file, no *.tmp-* leftover), the corpus folder gains and changes nothing, and
// inputs in {work} that the line aims outputs at are left byte for byte. Plus the
// regression tests of the bugs the corpus and the fuzzers found.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "io/json_strict.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fs::path(PINMASK_SOURCE_DIR) / "tests" / "bad-inputs";
const fs::path kValidMask = fs::path(PINMASK_SOURCE_DIR) / "fuzz/corpus/mask_json/small.mask.json";
const fs::path kValidCapture = fs::path(PINMASK_SOURCE_DIR) / "fuzz/corpus/image/cap.npy";
const fs::path kValidRaw = fs::path(PINMASK_SOURCE_DIR) / "fuzz/corpus/raw/small.dng";

struct ManifestLine {
    int line_number = 0;
    std::string file;     // "-" when the bad input is on the command line
    std::string command;  // "[NAME=VALUE ...] pinmask ARGS" with {in} {out} {dir} {mask} ...
    std::string expect;   // fragment of the message
    int exit_code = 2;
};

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> split_columns(const std::string& line) {
    std::vector<std::string> cols;
    std::size_t start = 0;
    for (std::size_t at; (at = line.find(" | ", start)) != std::string::npos; start = at + 3) {
        cols.push_back(trim(line.substr(start, at - start)));
    }
    cols.push_back(trim(line.substr(start)));
    return cols;
}

std::vector<ManifestLine> read_manifest() {
    std::ifstream in(kCorpus / "manifest.txt");
    REQUIRE(in);
    std::vector<ManifestLine> lines;
    std::string text;
    for (int n = 1; std::getline(in, text); ++n) {
        text = trim(text);
        if (text.empty() || text[0] == '#') continue;
        const auto cols = split_columns(text);
        INFO("manifest.txt line " << n << ": " << text);
        REQUIRE((cols.size() == 3 || cols.size() == 4));
        ManifestLine m{n, cols[0], cols[1], cols[2]};
        if (cols.size() == 4) m.exit_code = std::stoi(cols[3]);
        lines.push_back(m);
    }
    return lines;
}

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

void replace_all(std::string& s, const std::string& from, const std::string& to) {
    for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) {
        s.replace(at, from.size(), to);
    }
}

// The shell command of a manifest line: placeholders filled, "pinmask" replaced by the
// executable (environment assignments before it stay in front).
// {work}: a folder of valid inputs, made fresh for each line: cam.json, m.mask.json and
// e.export.json (a mask),
// c.npy (a capture), p.tiff with its sidecar p.json (a PSF). Lines aim outputs at these inputs;
// afterwards the folder must hold exactly these files, byte for byte.
// {taken}: a folder where the names taken.tiff, taken.npy, taken.png, taken.json, taken.pdf,
// taken.svg, taken.mask.json, o.png.config.json and o.tiff.config.json are directories.
const std::vector<std::pair<std::string, fs::path>> kWorkFiles = {
    {"cam.json", kValidMask},
    {"m.mask.json", kValidMask},
    {"c.npy", kValidCapture},
    {"p.tiff", fs::path(PINMASK_SOURCE_DIR) / "fuzz/corpus/image/psf_box.tiff"},
    {"p.json", fs::path(PINMASK_SOURCE_DIR) / "fuzz/corpus/psf_sidecar/psf_box.json"},
    {"e.export.json", kValidMask}};
const std::vector<std::string> kTakenNames = {
    "taken.tiff", "taken.npy",       "taken.png",         "taken.json",        "taken.pdf",
    "taken.svg",  "taken.mask.json", "o.png.config.json", "o.tiff.config.json"};

// {special}: special files in place of inputs and outputs, made once: named pipes (pipe.npy,
// pipe.tiff, pipe.json, pipe.txt, pipe.mask.json, pipe.png), symbolic links to /dev/null
// (null.json, null.png, null.tiff) and /dev/zero (zero.txt, zero.npy), and a PSF whose sidecar
// is a pipe (s.tiff + s.json). Reading a pipe would block the test (it has no writer), so a line
// that reads one hangs instead of failing; afterwards each name must still be what it was.
const std::vector<std::string> kPipeNames = {"pipe.npy",       "pipe.tiff", "pipe.json", "pipe.txt",
                                             "pipe.mask.json", "pipe.png",  "s.json"};
const std::vector<std::pair<std::string, std::string>> kDeviceLinks = {{"null.json", "/dev/null"},
                                                                       {"null.png", "/dev/null"},
                                                                       {"null.tiff", "/dev/null"},
                                                                       {"zero.txt", "/dev/zero"},
                                                                       {"zero.npy", "/dev/zero"}};

void make_special(const fs::path& dir) {
    for (const auto& name : kPipeNames) REQUIRE(::mkfifo((dir / name).c_str(), 0600) == 0);
    for (const auto& [name, target] : kDeviceLinks) fs::create_symlink(target, dir / name);
    fs::copy_file(fs::path(PINMASK_SOURCE_DIR) / "fuzz/corpus/image/psf_box.tiff", dir / "s.tiff");
}

// The type of every entry (never its contents: a pipe cannot be read).
std::map<std::string, std::string> kinds_in(const fs::path& dir) {
    std::map<std::string, std::string> kinds;
    for (const auto& e : fs::directory_iterator(dir)) {
        const auto st = fs::symlink_status(e.path());
        std::string kind = fs::is_fifo(st)      ? "fifo"
                           : fs::is_symlink(st) ? "link:" + fs::read_symlink(e.path()).string()
                           : fs::is_regular_file(st)
                               ? "file:" + std::to_string(fs::file_size(e.path()))
                               : "other";
        kinds[e.path().filename().string()] = kind;
    }
    return kinds;
}

std::map<std::string, std::string> contents_of(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::directory_iterator(dir)) {
        files[e.path().filename().string()] =
            e.is_directory() ? "<dir>" : pinmask::test::slurp(e.path());
    }
    return files;
}

std::string shell_command(const ManifestLine& m, const TempDir& out, const TempDir& work,
                          const TempDir& taken, const TempDir& special) {
    std::string cmd = m.command;
    replace_all(cmd, "{special}", quoted(special.path));
    replace_all(cmd, "{work}", quoted(work.path));
    replace_all(cmd, "{taken}", quoted(taken.path));
    if (m.file != "-") replace_all(cmd, "{in}", quoted(kCorpus / m.file));
    replace_all(cmd, "{out}", quoted(out.path / "out"));
    replace_all(cmd, "{dir}", quoted(out.path));
    replace_all(cmd, "{mask}", quoted(kValidMask));
    replace_all(cmd, "{mask_capture}", quoted(kValidCapture));
    replace_all(cmd, "{raw_capture}", quoted(kValidRaw));
    const auto at = cmd.find("pinmask ");
    REQUIRE(at != std::string::npos);
    // coreutils timeout: a line that blocks (a pipe read by mistake) fails with 124 instead of
    // hanging the suite. A guard against a hang, not a timing assertion.
    cmd.replace(at, 7, std::string("timeout -k 10 600 ") + PINMASK_EXE);
    return cmd;
}

struct Run {
    int exit_code = -1;
    std::string output;  // stdout then stderr
};

Run run_shell(const std::string& cmd, const TempDir& scratch) {
    const fs::path out = scratch.path / "stdout", err = scratch.path / "stderr";
    const std::string full = cmd + " >" + quoted(out) + " 2>" + quoted(err) + " </dev/null";
    const int status = std::system(full.c_str());
    Run r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.output = pinmask::test::slurp(out) + pinmask::test::slurp(err);
    return r;
}

std::set<std::string> names_in(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

}  // namespace

TEST_CASE("every malformed input is refused: expected exit code, a message, no output left") {
    const auto lines = read_manifest();
    const auto corpus_before = contents_of(kCorpus);
    TempDir scratch("bad-inputs-log");
    TempDir taken("bad-inputs-taken");
    for (const auto& name : kTakenNames) fs::create_directories(taken.path / name);
    const auto taken_before = contents_of(taken.path);
    TempDir special("bad-inputs-special");
    make_special(special.path);
    const auto special_before = kinds_in(special.path);
    for (const ManifestLine& m : lines) {
        TempDir out("bad-inputs");
        TempDir work("bad-inputs-work");
        for (const auto& [name, from] : kWorkFiles) fs::copy_file(from, work.path / name);
        const auto work_before = contents_of(work.path);
        const std::string cmd = shell_command(m, out, work, taken, special);
        INFO("manifest.txt line " << m.line_number << ": " << m.file << " | " << m.command);
        const Run r = run_shell(cmd, scratch);
        INFO("output: " << r.output);
        CHECK(r.exit_code == m.exit_code);
        CHECK(r.output.find(m.expect) != std::string::npos);
        std::string left;
        for (const auto& name : names_in(out.path)) left += name + " ";
        CHECK_MESSAGE(left.empty(), "left in the output folder: " << left);
        CHECK_MESSAGE(contents_of(work.path) == work_before, "an input in {work} was changed");
        CHECK_MESSAGE(contents_of(taken.path) == taken_before, "{taken} was changed");
        CHECK_MESSAGE(kinds_in(special.path) == special_before, "{special} was changed");
    }
    CHECK(contents_of(kCorpus) == corpus_before);  // no file added, none changed
}

TEST_CASE("the manifest covers every file of the corpus") {
    const auto lines = read_manifest();
    std::set<std::string> named;
    for (const ManifestLine& m : lines) named.insert(m.file);
    std::size_t files = 0;
    for (const auto& name : names_in(kCorpus)) {
        if (name == "manifest.txt" || name == "generate.py") continue;
        ++files;
        fs::path as_tiff = name;  // a PSF sidecar is read through its .tiff
        as_tiff.replace_extension(".tiff");
        bool sidecar = fs::path(name).extension() == ".json" &&
                       name.find(".mask.json") == std::string::npos &&
                       named.count(as_tiff.string());
        // An export sidecar NAME.export.json is read through the fabrication file NAME.<ext>
        // beside it (check reads it by that name).
        if (const std::string tail = ".export.json"; name.ends_with(tail)) {
            const std::string stem = name.substr(0, name.size() - tail.size()) + ".";
            for (const std::string& n : named)
                if (n.starts_with(stem) && n.find('.', stem.size()) == std::string::npos)
                    sidecar = true;
        }
        INFO(name);
        CHECK((named.count(name) == 1 || sidecar));
        CHECK(name.find(".tmp-") == std::string::npos);
    }
    // The corpus is as large as docs/reliability.md says (update both together).
    CHECK(files >= 60);
}

// Regression (found by the bad-input corpus): parse_strict kept the key path of every open
// level, so nesting cost O(depth^2) bytes: 50k '[' took 4.5 GB and 40 s. Now refused at depth 64.
TEST_CASE("parse_strict refuses deep nesting at once") {
    using pinmask::io::json_strict::parse_strict;
    const std::size_t depth = 200000;
    const std::string arrays = std::string(depth, '[') + std::string(depth, ']');
    std::string objects;  // {"a": {"a": ... 1 ... }}
    for (std::size_t i = 0; i < depth / 10; ++i) objects += "{\"a\":";
    objects += "1" + std::string(depth / 10, '}');
    for (const std::string& text : {arrays, objects}) {
        CHECK_THROWS_WITH_AS(parse_strict(text), doctest::Contains("nesting deeper than 64"),
                             pinmask::InvalidInput);
    }
    // 64 levels are still accepted.
    CHECK_NOTHROW(parse_strict(std::string(64, '[') + std::string(64, ']')));
}
