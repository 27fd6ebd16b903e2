// io/json_strict read_bounded_file and parse_bounded_file: a file of exactly the limit is read
// whole, one byte more is refused before reading with the limit in MiB / GiB / KiB / bytes, a
// missing file is refused, and the parser's refusals are prefixed with "<setting> <path>: ".
// The three configuration readers (search config, sweep file, checkpoint) go through it.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors/error.hpp"
#include "io/checkpoint.hpp"
#include "io/json_strict.hpp"
#include "io/search_config.hpp"
#include "io/sweep_config.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using io::json_strict::parse_bounded_file;
using io::json_strict::read_bounded_file;

namespace {

void write_file(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// The message of the refusal, or "accepted".
template <class Read>
std::string refusal(Read read) {
    try {
        read();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "accepted";
}

}  // namespace

TEST_CASE("read_bounded_file: the whole text up to the limit, refused one byte beyond it") {
    test::TempDir dir("bounded");
    const std::string path = dir / "f.json";
    const std::string text(10, 'x');
    write_file(path, text);
    CHECK(read_bounded_file(path, "--config " + path, 10, "a search configuration") == text);
    CHECK(refusal([&] { read_bounded_file(path, "--config " + path, 9, "a thing"); }) ==
          "--config " + path + ": 10 bytes is not a thing (at most 9 bytes)");
}

TEST_CASE("read_bounded_file: the limit stated in the largest whole binary unit") {
    test::TempDir dir("bounded-units");
    const std::string path = dir / "f.json";
    write_file(path, std::string(2049, 'x'));
    const auto message = [&](std::uintmax_t max) {
        return refusal([&] { read_bounded_file(path, "W", max, "a file"); });
    };
    CHECK(message(2048) == "W: 2049 bytes is not a file (at most 2 KiB)");
    CHECK(message(2000) == "W: 2049 bytes is not a file (at most 2000 bytes)");
    write_file(path, std::string((1 << 20) + 1, 'x'));
    CHECK(message(1 << 20) ==
          "W: " + std::to_string((1 << 20) + 1) + " bytes is not a file (at most 1 MiB)");
}

TEST_CASE("read_bounded_file: a missing file is refused naming the setting and the path") {
    test::TempDir dir("bounded-missing");
    const std::string path = dir / "missing.json";
    const std::string m = refusal([&] { read_bounded_file(path, "SWEEP " + path, 100, "x"); });
    CHECK(m.rfind("SWEEP " + path + ": cannot read: ", 0) == 0);
}

TEST_CASE("parse_bounded_file: the parser's result, or its refusal prefixed") {
    test::TempDir dir("bounded-parse");
    const std::string path = dir / "f.txt";
    write_file(path, "42");
    const auto to_int = [](const std::string& t) { return std::stoi(t); };
    CHECK(parse_bounded_file(path, "SET", 100, "a number", to_int) == 42);
    const auto refuse = [](const std::string&) -> int { throw InvalidInput("key: rule"); };
    CHECK(refusal([&] { parse_bounded_file(path, "SET", 100, "a number", refuse); }) ==
          "SET " + path + ": key: rule");
}

TEST_CASE("the configuration readers: their setting, kind and limit in every message") {
    test::TempDir dir("bounded-readers");
    const std::string path = dir / "big.json";
    write_file(path, std::string((1 << 20) + 1, ' '));
    const std::string size = std::to_string((1 << 20) + 1);
    CHECK(refusal([&] { io::read_sweep_config(path); }) ==
          "SWEEP " + path + ": " + size + " bytes is not a sweep file (at most 1 MiB)");
    CHECK(refusal([&] {
              io::read_search_config(path);
          }).find(path + ": " + size + " bytes is not a search configuration (at most 1 MiB)") !=
          std::string::npos);
    // Within its 1 GiB limit the checkpoint reader parses the text and prefixes the refusal.
    write_file(path, "{}");
    const std::string m = refusal([&] { io::read_checkpoint(path); });
    CHECK(m.find(path + ": ") != std::string::npos);
    CHECK(m != "accepted");
}
