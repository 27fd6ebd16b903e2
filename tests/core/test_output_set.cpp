// Output-set planning and the all-or-nothing commit (core/files/output_set,
// core/files/atomic_file): outputs that are directories, inputs (by any spelling or a hard link) or
// each other are refused before any work, naming the flag; a commit whose rename fails removes the
// files already renamed, restores the files it replaced and says so.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_set.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
namespace fs = std::filesystem;
using pinmask::test::slurp;
using pinmask::test::TempDir;

namespace {

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

int count_files(const fs::path& dir) {
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
    return n;
}

}  // namespace

TEST_CASE("plan_outputs refuses an output that is an input, under any spelling or a hard link") {
    TempDir t("outset-input");
    const fs::path in = t.path / "cam.json";
    write_text(in, "{}");
    fs::create_directories(t.path / "sub");
    const std::string spelled = (t.path / "sub" / ".." / "cam.json").string();
    const std::string msg = message_of([&] {
        plan_outputs({{"mask", in}}, {{"-o (sidecar)", spelled}});
    });
    CHECK(msg.find("-o (sidecar)") != std::string::npos);
    CHECK(msg.find("also the input mask") != std::string::npos);
    fs::create_hard_link(in, t.path / "link.json");
    CHECK_THROWS_AS(plan_outputs({{"mask", in}}, {{"-o", t.path / "link.json"}}), InvalidInput);
    CHECK(slurp(in) == "{}");
    reset_input_protection();  // plan_outputs turned it on
}

TEST_CASE("plan_outputs refuses two outputs with one name, a directory and an unwritable folder") {
    TempDir t("outset-dup");
    const fs::path o = t.path / "o.npy";
    const std::string dup = message_of([&] { plan_outputs({}, {{"-o", o}, {"--stats", o}}); });
    CHECK(dup.find("--stats") != std::string::npos);
    CHECK(dup.find("also the output -o") != std::string::npos);
    fs::create_directories(t.path / "adir");
    const std::string dir = message_of([&] { plan_outputs({}, {{"-o", t.path / "adir"}}); });
    CHECK(dir.find("existing directory") != std::string::npos);
    write_text(t.path / "afile", "x");
    const std::string parent = message_of([&] {
        plan_outputs({}, {{"-o", t.path / "afile" / "x" / "o.tiff"}});
    });
    CHECK(parent.find("is a file, not a directory") != std::string::npos);
    if (::geteuid() != 0) {  // root may write anywhere
        fs::create_directories(t.path / "ro");
        fs::permissions(t.path / "ro", fs::perms::owner_read | fs::perms::owner_exec);
        CHECK_THROWS_AS(plan_outputs({}, {{"-o", t.path / "ro" / "o.tiff"}}), InvalidInput);
        fs::permissions(t.path / "ro", fs::perms::owner_all);
    }
    // A missing folder is refused, unless the command creates it (export's and search's -o)
    // below a writable one; empty names are skipped (optional outputs not asked for), except -o.
    const std::string missing = message_of([&] {
        plan_outputs({}, {{"--stats", t.path / "new" / "o.json"}});
    });
    CHECK(missing.find("does not exist") != std::string::npos);
    CHECK_NOTHROW(
        plan_outputs({{"mask", ""}}, {{"-o", t.path / "new" / "o.tiff", true}, {"--stats", ""}}));
    CHECK_THROWS_AS(plan_outputs({}, {{"-o", ""}}), InvalidInput);
    reset_input_protection();
}

TEST_CASE("StagedFiles refuses a protected input, a directory and a name staged twice") {
    TempDir t("outset-staged");
    const fs::path in = t.path / "in.json";
    write_text(in, "input");
    enable_input_protection();
    protect_input(in);
    {
        StagedFiles files;
        CHECK_THROWS_AS(files.stage_bytes(in, "x"), InvalidInput);
        files.stage_bytes(t.path / "a.txt", "a");
        CHECK_THROWS_AS(files.stage_bytes(t.path / "." / "a.txt", "b"), InvalidInput);
        fs::create_directories(t.path / "d");
        CHECK_THROWS_AS(files.stage_bytes(t.path / "d", "c"), InvalidInput);
    }  // not committed: the temporaries are removed
    CHECK(slurp(in) == "input");
    CHECK(count_files(t.path) == 2);  // in.json and d/
    CHECK_THROWS_AS(write_bytes_atomic(in, "y"), InvalidInput);
    CHECK(slurp(in) == "input");
    reset_input_protection();
    CHECK_NOTHROW(write_bytes_atomic(in, "y"));  // off again: a library user may rewrite inputs
}

TEST_CASE("a failed rename in commit removes the renamed files, restores old ones and says so") {
    TempDir t("outset-commit");
    write_text(t.path / "a.txt", "old a");  // replaced by the run, restored on failure
    for (int fail_at = 0; fail_at < 3; ++fail_at) {
        CAPTURE(fail_at);
        StagedFiles files;
        files.stage_bytes(t.path / "a.txt", "new a");
        files.stage_bytes(t.path / "b.txt", "new b");
        files.stage_bytes(t.path / "c.txt", "new c");
        StagedFiles::fail_rename_for_test(fail_at);
        std::string msg;
        try {
            files.commit();
        } catch (const RuntimeFailure& e) {
            msg = e.what();
        }
        CHECK(msg.find("could not write") != std::string::npos);
        if (fail_at > 0)
            CHECK(msg.find("removed the " + std::to_string(fail_at)) != std::string::npos);
        CHECK(slurp(t.path / "a.txt") == "old a");
        CHECK_FALSE(fs::exists(t.path / "b.txt"));
        CHECK_FALSE(fs::exists(t.path / "c.txt"));
    }
    CHECK(count_files(t.path) == 1);  // no temporary or backup left
    StagedFiles ok;
    ok.stage_bytes(t.path / "a.txt", "new a");
    ok.stage_bytes(t.path / "b.txt", "new b");
    ok.commit();
    CHECK(slurp(t.path / "a.txt") == "new a");
    CHECK(count_files(t.path) == 2);
}

TEST_CASE("a real rename failure (the final name became a directory) rolls back too") {
    TempDir t("outset-real");
    {
        StagedFiles files;
        files.stage_bytes(t.path / "a.txt", "a");
        files.stage_bytes(t.path / "b.txt", "b");
        fs::create_directories(t.path / "b.txt" / "inside");  // appears after staging
        CHECK_THROWS_AS(files.commit(), RuntimeFailure);
    }  // the group's destructor removes the temporary of b.txt
    CHECK_FALSE(fs::exists(t.path / "a.txt"));
    CHECK(fs::is_directory(t.path / "b.txt" / "inside"));
    CHECK(count_files(t.path) == 1);
}

TEST_CASE("an output that is a device, a pipe or a socket is refused and left as it was") {
    TempDir t("outset-special");
    const fs::path fifo = t.path / "pipe.json";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    std::string msg = message_of([&] { write_bytes_atomic(fifo, "x"); });
    CHECK(msg.find("is a named pipe") != std::string::npos);
    CHECK(fs::is_fifo(fifo));
    msg = message_of([&] { plan_outputs({}, {{"--stats", fifo}}); });
    CHECK(msg.find("--stats") != std::string::npos);
    CHECK(msg.find("named pipe") != std::string::npos);
    // /dev/null itself: refused before anything is written (a regression here would, as root,
    // replace the system's /dev/null; the check runs before any temporary exists).
    msg = message_of([&] {
        StagedFiles files;
        files.stage_bytes("/dev/null", "x");
    });
    CHECK(msg.find("is a character device") != std::string::npos);
    CHECK(fs::is_character_file("/dev/null"));
    // A symbolic link to a device is the device.
    fs::create_symlink("/dev/null", t.path / "null-link");
    CHECK(message_of([&] {
              write_bytes_atomic(t.path / "null-link", "x");
          }).find("character device") != std::string::npos);
    CHECK(fs::is_symlink(t.path / "null-link"));
    reset_input_protection();
}

TEST_CASE("a folder where no file can be created is refused by name before any work") {
    // /proc passes access(W_OK) for root but refuses every new name: found by a create and an
    // unlink in the folder (once per folder), not by a raw "cannot open" after the work.
    REQUIRE(fs::is_directory("/proc"));
    std::string msg = message_of([&] { plan_outputs({}, {{"-o", "/proc/x.tiff"}}); });
    CHECK(msg.find("-o") != std::string::npos);
    CHECK(msg.find("no file can be created in its folder '/proc'") != std::string::npos);
    msg = message_of([&] { write_bytes_atomic("/proc/x.json", "x"); });
    CHECK(msg.find("no file can be created in its folder '/proc'") != std::string::npos);
    // A folder that takes files is probed and left as it was: no probe file remains.
    TempDir t("outset-probe");
    plan_outputs({}, {{"-o", t.path / "a.json"}, {"--stats", t.path / "b.json"}});
    write_bytes_atomic(t.path / "c.json", "x");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(t.path)) names.push_back(e.path().filename());
    CHECK(names == std::vector<std::string>{"c.json"});
    reset_input_protection();
}

TEST_CASE("a file name too long for its temporary names is refused with the limit") {
    TempDir t("outset-long");
    const long name_max = ::pathconf(t.path.c_str(), _PC_NAME_MAX);
    REQUIRE(name_max > 64);
    const std::string fits(static_cast<std::size_t>(name_max - 64), 'a');
    write_bytes_atomic(t.path / fits, "ok");
    CHECK(slurp(t.path / fits) == "ok");
    const std::string too_long(static_cast<std::size_t>(name_max - 63), 'b');
    const std::string msg = message_of([&] { write_bytes_atomic(t.path / too_long, "x"); });
    CHECK(msg.find("bytes; this file system allows " + std::to_string(name_max)) !=
          std::string::npos);
    CHECK(count_files(t.path) == 1);
}

TEST_CASE("same_file_keys: two paths share a key exactly when same_file says they are one file") {
    TempDir t("outset-keys");
    write_text(t.path / "a.txt", "a");
    write_text(t.path / "b.txt", "b");
    fs::create_directories(t.path / "sub");
    fs::create_hard_link(t.path / "a.txt", t.path / "hard.txt");
    fs::create_symlink(t.path / "a.txt", t.path / "soft.txt");
    const std::vector<fs::path> paths = {
        t.path / "a.txt",          t.path / "b.txt",    t.path / "sub" / ".." / "a.txt",
        t.path / "hard.txt",       t.path / "soft.txt", t.path / "new.txt",
        t.path / "sub/../new.txt", t.path / "other.txt"};
    for (const fs::path& p : paths) {
        for (const fs::path& q : paths) {
            bool shared = false;
            for (const std::string& kp : same_file_keys(p))
                for (const std::string& kq : same_file_keys(q)) shared = shared || kp == kq;
            INFO(p.string() << " vs " << q.string());
            CHECK(shared == same_file(p, q));  // the pairwise reference the keys replace
        }
    }
}
