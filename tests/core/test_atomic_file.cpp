#include <doctest/doctest.h>

#include <filesystem>
#include <stdexcept>

#include "core/files/atomic_file.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
namespace fs = std::filesystem;

TEST_CASE("atomic write leaves nothing behind when the writer throws") {
    test::TempDir dir("atomic");
    const fs::path target = dir / "a.txt";
    CHECK_THROWS(write_file_atomic(target, [](const fs::path& tmp) {
        write_bytes_atomic(tmp, "partial");
        throw std::runtime_error("boom");
    }));
    CHECK(fs::is_empty(dir.path));
    write_bytes_atomic(target, "hello");
    CHECK(test::slurp(target) == "hello");
}

TEST_CASE("staged files appear together or not at all") {
    test::TempDir dir("staged");
    {
        StagedFiles files;
        files.stage_bytes(dir / "a", "1");
        files.stage_bytes(dir / "b", "2");
        // not committed
    }
    CHECK(fs::is_empty(dir.path));
    StagedFiles files;
    files.stage_bytes(dir / "a", "1");
    files.stage_bytes(dir / "b", "2");
    files.commit();
    CHECK(test::slurp(dir / "a") == "1");
    CHECK(test::slurp(dir / "b") == "2");
}

TEST_CASE("remove_pending_temporaries unlinks the temporaries in flight, and only those") {
    test::TempDir dir("pending");
    write_bytes_atomic(dir / "done.txt", "kept");
    // A temporary of write_file_atomic, seen from inside its writer (as a signal handler would).
    CHECK_THROWS(write_file_atomic(dir / "a.txt", [&](const fs::path& tmp) {
        write_bytes_atomic(tmp, "partial");  // the nested temporary is already renamed to tmp
        REQUIRE(fs::exists(tmp));
        remove_pending_temporaries();
        CHECK_FALSE(fs::exists(tmp));
        throw std::runtime_error("interrupted");
    }));
    // Staged files before their commit.
    {
        StagedFiles files;
        files.stage_bytes(dir / "b.txt", "2");
        files.stage_bytes(dir / "c.txt", "3");
        remove_pending_temporaries();
        int left = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path)) ++left;
        CHECK(left == 1);  // done.txt alone
    }
    // After a commit nothing is pending: the finals stay.
    {
        StagedFiles files;
        files.stage_bytes(dir / "d.txt", "4");
        files.commit();
        remove_pending_temporaries();
        CHECK(test::slurp(dir / "d.txt") == "4");
    }
    CHECK(test::slurp(dir / "done.txt") == "kept");
}
