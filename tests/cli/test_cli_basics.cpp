#include <doctest/doctest.h>

#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;

TEST_CASE("no subcommand and unknown flags are usage errors (exit 2)") {
    CHECK(run_cli("").exit_code == 2);
    CHECK(run_cli("--no-such-flag").exit_code == 2);
    const auto help = run_cli("--help");
    CHECK(help.exit_code == 0);
    CHECK(help.out.find("pinmask") != std::string::npos);
}
