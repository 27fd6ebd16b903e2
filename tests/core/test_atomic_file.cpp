#include <doctest/doctest.h>

#include <filesystem>
#include <stdexcept>

#include "core/atomic_file.hpp"
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
