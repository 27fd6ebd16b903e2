// `pinmask search` under mpirun, end to end on localhost: the same --evals command
// twice gives identical files on 2 and 3 ranks (3 oversubscribed on CI's 2 cores), one rank
// under mpirun equals the plain run, checkpointing changes nothing, a 2-rank run killed with
// SIGKILL after a checkpoint and resumed ends with the uninterrupted run's files, and a
// checkpoint of another configuration is refused naming the keys. timing.csv holds wall-clock
// samples and is the one file never compared.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// Anneal restarts are 20000 moves: 70000 evaluations a chain make three restart boundaries, where
// migration and checkpoints happen.
const std::string kArgs =
    " search --grid 12 --holes 8 --pixels-per-cell 4 --tiles 1 --prior-scenes 2 --threads 1 "
    "--top 3 --seed 2 --rerank-scenes letter-R --no-rerank-tv --quiet --evals 70000 ";

std::string mpirun(int ranks) {
    return std::string(PINMASK_MPIEXEC) + " -n " + std::to_string(ranks) + " --oversubscribe " +
           PINMASK_EXE;
}

int sh(const std::string& cmd) {
    const int status = std::system((cmd + " >/dev/null 2>&1 </dev/null").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The files of a search output folder but timing.csv (wall clock).
std::vector<std::pair<std::string, std::string>> outputs(const fs::path& dir) {
    std::vector<std::pair<std::string, std::string>> files;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().filename() == "timing.csv") continue;
        files.emplace_back(e.path().filename().string(), slurp(e.path()));
    }
    std::sort(files.begin(), files.end());
    return files;
}

void check_same(const fs::path& a, const fs::path& b) {
    const auto fa = outputs(a), fb = outputs(b);
    REQUIRE(fa.size() == fb.size());
    for (std::size_t i = 0; i < fa.size(); ++i) {
        const std::string name = fa[i].first;
        CAPTURE(name);
        CHECK(fb[i].first == name);
        CHECK(fb[i].second == fa[i].second);
    }
}

// The session id of a process (field 6 of /proc/PID/stat), -1 when it is gone.
long session_of(const fs::path& stat_file) {
    std::ifstream in(stat_file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto close = text.rfind(')');
    if (close == std::string::npos) return -1;
    std::istringstream rest(text.substr(close + 2));
    std::string state;
    long ppid = 0, pgrp = 0, session = -1;
    rest >> state >> ppid >> pgrp >> session;
    return session;
}

// SIGKILL to every process of session `sid` (mpirun started as its leader, and its ranks).
void kill_session(pid_t sid) {
    for (const auto& e : fs::directory_iterator("/proc")) {
        const std::string name = e.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        if (session_of(e.path() / "stat") == sid)
            ::kill(static_cast<pid_t>(std::stol(name)), SIGKILL);
    }
}

}  // namespace

TEST_CASE("mpirun search: 2 and 3 ranks reproducible; 1 rank equals the plain run") {
    TempDir dir("mpi-search");
    const std::string mig = " --migrate-every 20000 ";
    REQUIRE(run_cli(kArgs + mig + "-o " + (dir / "plain")).exit_code == 0);
    REQUIRE(sh(mpirun(1) + kArgs + mig + "-o " + (dir / "n1")) == 0);
    check_same(dir / "plain", dir / "n1");
    for (int ranks : {2, 3}) {
        const std::string a = dir / ("a" + std::to_string(ranks));
        const std::string b = dir / ("b" + std::to_string(ranks));
        REQUIRE(sh(mpirun(ranks) + kArgs + mig + "-o " + a) == 0);
        REQUIRE(sh(mpirun(ranks) + kArgs + mig + "-o " + b) == 0);
        check_same(a, b);
        // The summary counts every rank's chains.
        const std::string summary = slurp(fs::path(a) / "summary.md");
        CHECK(summary.find(std::to_string(70000 * ranks) + " evaluations") != std::string::npos);
        std::string per_chain = "per chain:";
        for (int r = 0; r < ranks; ++r) per_chain += " 70000";
        CHECK(summary.find(per_chain + "\n") != std::string::npos);
    }
    // Rank 1 ran other chains than rank 0 (seeds from (seed, rank)): the merged log differs.
    CHECK(slurp(dir / "a2/run-log.csv") != slurp(dir / "plain/run-log.csv"));
}

TEST_CASE(
    "mpirun search: killed after a checkpoint and resumed, the files equal the "
    "uninterrupted run's") {
    TempDir dir("mpi-resume");
    const std::string ck = " --migrate-every 20000 --checkpoint-every 20000 --checkpoint ";
    REQUIRE(sh(mpirun(2) + kArgs + ck + (dir / "full.ck") + " -o " + (dir / "full")) == 0);
    // Checkpoints change nothing in the work.
    REQUIRE(sh(mpirun(2) + kArgs + " --migrate-every 20000 -o " + (dir / "nock")) == 0);
    check_same(dir / "full", dir / "nock");

    const std::string cmd = mpirun(2) + kArgs + ck + (dir / "part.ck") + " -o " + (dir / "part");
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ::setsid();
        ::execl("/bin/sh", "sh", "-c", (cmd + " >/dev/null 2>&1").c_str(),
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    bool seen = false;
    for (int i = 0; i < 60000 && !seen; ++i) {  // polls until the file appears
        seen = fs::exists(dir / "part.ck");
        if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        int status;
        if (!seen && ::waitpid(pid, &status, WNOHANG) == pid) break;
    }
    kill_session(pid);
    ::waitpid(pid, nullptr, 0);
    REQUIRE(seen);
    // Killed before the end: nothing written to the output folder.
    CHECK_FALSE(fs::exists(fs::path(dir / "part") / "summary.md"));
    REQUIRE(sh(mpirun(2) + kArgs + ck + (dir / "part.ck") + " --resume " + (dir / "part.ck") +
               " -o " + (dir / "part")) == 0);
    check_same(dir / "full", dir / "part");

    // Another configuration: refused (exit 2) naming the differing keys, on 2 ranks and plain.
    std::string other = kArgs;
    other.replace(other.find("--seed 2"), 8, "--seed 3");
    const auto bad =
        run_cli(other + " --migrate-every 20000 --checkpoint-every 20000 --checkpoint " +
                (dir / "x.ck") + " --resume " + (dir / "full.ck") + " -o " + (dir / "x"));
    CAPTURE(bad.err);
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("differing keys: ranks, seed") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "x"));
    const std::string err = dir / "err.txt";
    const int rc = std::system((mpirun(2) + other + " --migrate-every 20000 --resume " +
                                (dir / "full.ck") + " -o " + (dir / "y") + " >/dev/null 2>" + err)
                                   .c_str());
    CHECK(WEXITSTATUS(rc) == 2);
    CHECK(slurp(err).find("differing keys: checkpoint_every, seed") != std::string::npos);
}

namespace {

// Starts `cmd` (exec'd by sh, so the pid is mpirun's) as the leader of a new session.
pid_t start_session(const std::string& cmd) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::setsid();
        ::execl("/bin/sh", "sh", "-c", ("exec " + cmd + " >/dev/null 2>&1").c_str(),
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    return pid;
}

// Polls (1 ms steps, up to 120 s) until `file` exists; false when the process ended first.
bool wait_for_file(const fs::path& file, pid_t pid) {
    for (int i = 0; i < 120000; ++i) {
        if (fs::exists(file)) return true;
        int status;
        if (::waitpid(pid, &status, WNOHANG) == pid) return fs::exists(file);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
}

// True when `pid` ended within 60 s (polled); the caller kills the session anyway.
bool wait_for_exit(pid_t pid) {
    for (int i = 0; i < 60000; ++i) {
        int status;
        if (::waitpid(pid, &status, WNOHANG) == pid) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
}

// No *.tmp-* file in `dir`.
bool no_temporaries(const fs::path& dir) {
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(".tmp-") != std::string::npos) return false;
    return true;
}

}  // namespace

// Open MPI's mpirun forwards a first SIGINT to the ranks and kills them on a second, before
// rank 0 has gathered and written the chains: a 60 s run given two Ctrl-C 0.1 s apart, and one
// killed with SIGKILL, each still leave a mask usable by the next command. Rank 0 writes
// best-so-far.mask.json as soon as its chains have a best (the test waits for that file, never
// for a time) and at once on the first signal.
TEST_CASE("mpirun search: two Ctrl-C to mpirun, or SIGKILL, leave the best so far") {
    TempDir dir("mpi-snapshot");
    const std::string args =
        " search --grid 12 --holes 8 --pixels-per-cell 4 --tiles 1 --prior-scenes 2 --threads 1 "
        "--seed 2 --no-rerank --quiet --time 60s -o ";
    // SIGKILL to mpirun and the ranks once the snapshot exists: it is a whole mask file.
    {
        const fs::path out = dir.path / "killed";
        const pid_t pid = start_session(mpirun(2) + args + out.string());
        REQUIRE(pid > 0);
        const bool seen = wait_for_file(out / "best-so-far.mask.json", pid);
        kill_session(pid);
        ::waitpid(pid, nullptr, 0);
        REQUIRE(seen);
        CHECK_FALSE(fs::exists(out / "summary.md"));
        const auto psf = run_cli("psf " + (out / "best-so-far.mask.json").string() + " -o " +
                                 (dir / "killed.tiff"));
        CAPTURE(psf.err);
        CHECK(psf.exit_code == 0);
        const std::string text = slurp(out / "best-so-far.mask.json");
        CHECK(text.find("search:anneal (best so far)") != std::string::npos);
        CHECK(text.find("search_objective") != std::string::npos);
    }
    // Two SIGINTs 0.1 s apart to mpirun (the reproduction of docs/reliability.md): whichever
    // way the race between rank 0's final write and mpirun's kill ends, the folder holds a usable
    // mask: the final files (rank-1.mask.json, best-so-far.mask.json removed) or the snapshot.
    {
        const fs::path out = dir.path / "twice";
        const pid_t pid = start_session(mpirun(2) + args + out.string());
        REQUIRE(pid > 0);
        const bool seen = wait_for_file(out / "best-so-far.mask.json", pid);
        ::kill(pid, SIGINT);
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        ::kill(pid, SIGINT);
        const bool ended = wait_for_exit(pid);
        kill_session(pid);
        if (!ended) ::waitpid(pid, nullptr, 0);
        REQUIRE(seen);
        CHECK(ended);
        const bool final_files = fs::exists(out / "summary.md");
        const fs::path mask = out / (final_files ? "rank-1.mask.json" : "best-so-far.mask.json");
        const std::string outcome = final_files ? "final files written" : "snapshot kept";
        MESSAGE("two SIGINTs: ", outcome);
        REQUIRE(fs::exists(mask));
        if (final_files) CHECK_FALSE(fs::exists(out / "best-so-far.mask.json"));
        CHECK(no_temporaries(out));
        const auto psf = run_cli("psf " + mask.string() + " -o " + (dir / "twice.tiff"));
        CAPTURE(psf.err);
        CHECK(psf.exit_code == 0);
    }
}
