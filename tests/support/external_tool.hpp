// The optional external tools of the cross-check tests (klayout, gerbv, python3-ezdxf,
// rsvg-convert, poppler-utils): whether one is installed, and running one. A test whose tool is
// absent says so in a MESSAGE naming the package and checks nothing else.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>

#include "tests/support/cli_run.hpp"

namespace pinmask::test {

// True when the shell command `probe` exits 0 (its output discarded), e.g. "gerbv --version".
inline bool have_tool(const std::string& probe) {
    return std::system((probe + " >/dev/null 2>&1").c_str()) == 0;
}

// Runs a shell command with its stdout and stderr in `dir` (tool.out, tool.err): its exit
// status (-1 when it did not exit normally) and stdout.
inline std::pair<int, std::string> run_tool(const std::string& cmd, const TempDir& dir) {
    const std::string out = dir / "tool.out";
    const int status = std::system((cmd + " >" + out + " 2>" + (dir / "tool.err")).c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out)};
}

inline void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace pinmask::test
