// Long runs stopped by SIGINT or SIGTERM once they have made progress exit 0, say they were
// interrupted, and leave complete, valid outputs with no *.tmp-* file:
//  - `pinmask search --time 60s`: rank-1.mask.json readable, run-log.csv, search.config.json
//    (documented: "Ctrl-C stops and writes the best so far");
//  - `pinmask decode --method tv|tvqc|rl` with an iteration budget it cannot finish: the estimate
//    after the iterations done, its config, and stats marked "interrupted".
// The commands run on a pseudo-terminal so their progress output (drawn only on a terminal)
// tells the test that work has started before the signal is sent.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/outputs/interrupt.hpp"
#include "core/files/atomic_file.hpp"
#include "io/mask_json.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

// Generous guard against a hang (not a timing assertion): sanitizer builds start slowly.
constexpr double kGiveUpSeconds = 120.0;
// The signal goes out once the progress line reports this much searching (its seconds field,
// printed rounded to whole seconds), as a user would press Ctrl-C during a run.
constexpr double kProgressSeconds = 1.0;

struct Child {
    pid_t pid = -1;
    int pty = -1;  // master side: the child's stderr
};

// Starts pinmask with stderr on a new pseudo-terminal, stdout into out_file.
Child start(const std::string& args, const fs::path& out_file) {
    Child c;
    c.pty = ::posix_openpt(O_RDWR | O_NOCTTY);
    REQUIRE(c.pty >= 0);
    REQUIRE(::grantpt(c.pty) == 0);
    REQUIRE(::unlockpt(c.pty) == 0);
    const std::string slave = ::ptsname(c.pty);
    c.pid = ::fork();
    REQUIRE(c.pid >= 0);
    if (c.pid == 0) {
        const int err = ::open(slave.c_str(), O_RDWR | O_NOCTTY);
        const int out = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int in = ::open("/dev/null", O_RDONLY);
        if (err < 0 || out < 0 || in < 0) ::_exit(127);
        ::dup2(in, 0);
        ::dup2(out, 1);
        ::dup2(err, 2);
        const std::string cmd = std::string("exec ") + PINMASK_EXE + " " + args;
        ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    return c;
}

// True when the last progress line on the terminal ("\r[###...] 12% best -19.4570, 3.1e+03
// evals/s, 2 s") shows a finite best objective after at least kProgressSeconds of searching.
bool searched_long_enough(const std::string& seen) {
    const auto line = seen.rfind("best ");
    const auto rate = seen.rfind(" evals/s, ");
    if (line == std::string::npos || rate == std::string::npos || rate < line) return false;
    const char first = seen[line + 5];
    if (first != '-' && (first < '0' || first > '9')) return false;  // "best inf": no evaluation
    const double seconds = std::atof(seen.c_str() + rate + 10);
    return seconds >= kProgressSeconds;
}

// Reads the child's terminal until `done(seen)` holds (true), or the child ends / time runs out.
template <typename Done>
bool wait_for_progress(const Child& c, std::string& seen, Done done) {
    const auto t0 = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - t0).count() < kGiveUpSeconds) {
        pollfd p{c.pty, POLLIN, 0};
        if (::poll(&p, 1, 200) > 0) {
            char buf[4096];
            const ssize_t n = ::read(c.pty, buf, sizeof buf);
            if (n <= 0) return false;  // the child closed its terminal (it ended)
            seen.append(buf, static_cast<std::size_t>(n));
            if (done(seen)) return true;
        }
    }
    return false;
}

// Waits for the child, draining its terminal so it never blocks on a full buffer.
int wait_exit(const Child& c, std::string& seen) {
    const auto t0 = Clock::now();
    int status = 0;
    while (::waitpid(c.pid, &status, WNOHANG) == 0) {
        if (std::chrono::duration<double>(Clock::now() - t0).count() > kGiveUpSeconds) {
            ::kill(c.pid, SIGKILL);
            ::waitpid(c.pid, &status, 0);
            return -1;
        }
        pollfd p{c.pty, POLLIN, 0};
        if (::poll(&p, 1, 50) > 0) {
            char buf[4096];
            const ssize_t n = ::read(c.pty, buf, sizeof buf);
            if (n > 0) seen.append(buf, static_cast<std::size_t>(n));
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Waits until `ready(terminal text)`, sends `sig`, then checks that the run ends by itself with
// exit code 0 and says it was interrupted.
template <typename Ready>
void interrupt_when(const Child& c, int sig, Ready ready) {
    std::string seen;
    const bool progressed = wait_for_progress(c, seen, ready);
    INFO("terminal: " << seen);
    CHECK(progressed);
    ::kill(c.pid, sig);
    const int code = wait_exit(c, seen);
    ::close(c.pty);
    CHECK(code == 0);
    CHECK(seen.find("interrupted") != std::string::npos);
}

}  // namespace

TEST_CASE("search stops cleanly on SIGINT and SIGTERM with the best so far written") {
    for (const int sig : {SIGINT, SIGTERM}) {
        INFO("signal " << sig);
        TempDir dir("search-interrupt");
        const fs::path out = dir.path / "run";
        const Child c = start(
            "search --grid 16 --holes 12 --pixels-per-cell 4 --time 60s "
            "--threads 1 --prior-scenes 2 --top 3 --seed 2 -o '" +
                out.string() + "'",
            dir.path / "stdout.txt");
        interrupt_when(c, sig, searched_long_enough);
        REQUIRE(fs::exists(out / "rank-1.mask.json"));
        CHECK_NOTHROW(pinmask::io::read_mask_file(out / "rank-1.mask.json"));
        CHECK(fs::exists(out / "run-log.csv"));
        CHECK(fs::exists(out / "search.config.json"));
        for (const auto& e : fs::recursive_directory_iterator(dir.path)) {
            INFO(e.path().string());
            CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
        }
    }
}

// `timeout 3 pinmask search ...` sends SIGTERM to the process and again to its
// group. Two signals back to back must still end with the best so far written: the second only
// hurries the run.
TEST_CASE("search: two SIGTERMs back to back still write the best so far") {
    TempDir dir("search-interrupt-twice");
    const fs::path out = dir.path / "run";
    const Child c = start(
        "search --grid 16 --holes 12 --pixels-per-cell 4 --time 60s --threads 1 --prior-scenes 2 "
        "--top 3 --seed 4 -o '" +
            out.string() + "'",
        dir.path / "stdout.txt");
    std::string seen;
    REQUIRE(wait_for_progress(c, seen, searched_long_enough));
    ::kill(c.pid, SIGTERM);
    ::kill(c.pid, SIGTERM);
    const int code = wait_exit(c, seen);
    ::close(c.pty);
    INFO("terminal: " << seen);
    CHECK(code == 0);
    CHECK(seen.find("interrupted") != std::string::npos);
    REQUIRE(fs::exists(out / "rank-1.mask.json"));
    CHECK_NOTHROW(pinmask::io::read_mask_file(out / "rank-1.mask.json"));
    CHECK(fs::exists(out / "summary.md"));
}

TEST_CASE("decode stops iterating on SIGINT and SIGTERM and writes the estimate so far") {
    const std::string src = PINMASK_SOURCE_DIR;
    const std::string mask = src + "/fuzz/corpus/mask_json/small.mask.json";
    const std::string capture = src + "/fuzz/corpus/image/cap.npy";
    for (const int sig : {SIGINT, SIGTERM}) {
        for (const std::string method : {"tv", "tvqc", "richardson-lucy"}) {
            INFO("signal " << sig << ", method " << method);
            TempDir dir("decode-interrupt");
            const fs::path out = dir.path / "scene.png", stats = dir.path / "stats.json";
            // 10^9 iterations at tolerance 0: only the signal can end it.
            const Child c = start("decode '" + capture + "' --mask '" + mask + "' --method " +
                                      method + (method == "tvqc" ? " --eps 0.01" : "") +
                                      " --iters 1000000000 --tol 0 -o '" + out.string() +
                                      "' --stats '" + stats.string() + "'",
                                  dir.path / "stdout.txt");
            interrupt_when(c, sig, [](const std::string& seen) {
                return seen.find("Ctrl-C stops") != std::string::npos;
            });
            REQUIRE(fs::exists(out));
            CHECK(fs::exists(out.string() + ".config.json"));
            REQUIRE(fs::exists(stats));
            const auto j = nlohmann::json::parse(slurp(stats));
            CHECK(j.at("interrupted") == true);
            for (const auto& ch : j.at("channels")) {
                CHECK(ch.at("interrupted") == true);
                CHECK(ch.at("converged") == false);
                CHECK(ch.at("iterations").get<long long>() >= 1);
                CHECK(ch.at("iterations").get<long long>() < 1000000000LL);
            }
            for (const auto& e : fs::recursive_directory_iterator(dir.path)) {
                INFO(e.path().string());
                CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
            }
        }
    }
}

// Commands that do not stop cleanly on a signal (export, psf, check, ...) die of it, but first
// unlink their temporary files (cli/outputs/interrupt install_cleanup_on_signal, which
// cli/main.cpp installs). The signal arrives in the middle of an atomic write, deterministically:
// the child raises it from inside the writer, after the temporary file holds data.
TEST_CASE("a fatal signal during an atomic write leaves neither the file nor a temporary") {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        TempDir t("cleanup-signal");
        const fs::path target = t.path / "mask.svg";
        const pid_t pid = ::fork();
        REQUIRE(pid >= 0);
        if (pid == 0) {
            pinmask::cli::install_cleanup_on_signal();
            pinmask::write_file_atomic(target, [sig](const fs::path& tmp) {
                pinmask::write_bytes_atomic(tmp, std::string(1 << 16, 'x'));
                ::raise(sig);
            });
            ::_exit(0);  // not reached: the signal ends the process
        }
        int status = 0;
        REQUIRE(::waitpid(pid, &status, 0) == pid);
        INFO("signal " << sig);
        CHECK(WIFSIGNALED(status));
        CHECK(WTERMSIG(status) == sig);  // it died of the signal, as without the handler
        CHECK(fs::is_empty(t.path));
    }
}
