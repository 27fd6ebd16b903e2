// core/files/output_folder: an output folder created when missing (its missing parents too) and
// removed again, level by level, when the run ends without writing into it; an existing parent,
// a folder the run wrote into and a kept folder stay; a file under the name is refused.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <optional>

#include "core/errors/error.hpp"
#include "core/files/output_folder.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::CreatedOutputFolder;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

TEST_CASE("CreatedOutputFolder creates what is missing and removes only that, only when empty") {
    TempDir t("outfolder");
    const fs::path deep = t.path / "a" / "b" / "c";
    {
        CreatedOutputFolder f(deep, "-o");
        CHECK_FALSE(fs::exists(t.path / "a"));  // nothing before create()
        f.create();
        CHECK(fs::is_directory(deep));
    }
    CHECK_FALSE(fs::exists(t.path / "a"));  // every level it made, removed
    fs::create_directory(t.path / "a");
    {
        CreatedOutputFolder f(t.path / "a" / "b" / "", "-o");  // a trailing separator
        f.create();
        CHECK(fs::is_directory(t.path / "a" / "b"));
    }
    CHECK(fs::is_directory(t.path / "a"));  // it existed before: stays
    CHECK_FALSE(fs::exists(t.path / "a" / "b"));
    {
        CreatedOutputFolder f(deep, "-o");
        f.create();
        std::ofstream(deep / "x.tiff") << "written";  // the run wrote into it
    }
    CHECK(fs::exists(deep / "x.tiff"));
    fs::remove_all(t.path / "a" / "b");
    {
        CreatedOutputFolder f(deep, "-o");
        f.create();
        f.keep();
    }
    CHECK(fs::is_directory(deep));  // kept though empty
    {
        CreatedOutputFolder f(deep, "-o");  // exists already: nothing to remove
        f.create();
    }
    CHECK(fs::is_directory(deep));
    std::ofstream(t.path / "file") << "x";
    CHECK_THROWS_WITH_AS(CreatedOutputFolder(t.path / "file", "-o"),
                         doctest::Contains("is a file; give a folder (created when missing)"),
                         pinmask::InvalidInput);
    CHECK_THROWS_WITH_AS(CreatedOutputFolder("", "--out"), doctest::Contains("--out"),
                         pinmask::InvalidInput);
    // A file where a parent should be: create() fails naming the flag, and removes what it made.
    {
        CreatedOutputFolder f(t.path / "file" / "sub", "-o");
        CHECK_THROWS_WITH_AS(f.create(), doctest::Contains("-o: cannot create the folder"),
                             pinmask::RuntimeFailure);
    }
    CHECK(fs::is_regular_file(t.path / "file"));
}
