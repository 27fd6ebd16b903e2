// Every command of the README's tour runs, in order, in an empty folder, and exits 0.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_run.hpp"

namespace {

std::vector<std::string> tour_commands() {
    std::ifstream in(std::string(PINMASK_SOURCE_DIR) + "/README.md");
    std::string line;
    bool inside = false;
    std::vector<std::string> commands;
    while (std::getline(in, line)) {
        if (line.find("<!-- tour:begin -->") != std::string::npos) inside = true;
        if (line.find("<!-- tour:end -->") != std::string::npos) inside = false;
        if (inside && line.rfind("pinmask ", 0) == 0) commands.push_back(line.substr(8));
    }
    return commands;
}

}  // namespace

TEST_CASE("the README tour runs in order and every command exits 0") {
    const auto commands = tour_commands();
    REQUIRE(commands.size() >= 10);
    pinmask::test::TempDir dir("readme-tour");
    for (const auto& args : commands) {
        const auto r = pinmask::test::run_cli(args, dir.path);
        INFO("pinmask " << args << "\nstderr: " << r.err);
        CHECK(r.exit_code == 0);
    }
}
