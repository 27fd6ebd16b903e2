// core/files/isolated_call: answers cross from the child intact (values known by construction, a
// payload larger than any pipe buffer), errors keep their class and message, and every way a
// child can die (signal, abort, exit status, death mid-answer or after it) becomes IsolatedCrash
// naming how; the caller's process survives and no child is left behind.
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <new>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/files/isolated_call.hpp"

using namespace pinmask;

namespace {

// No child of this process is left running or unreaped.
bool no_children_left() { return ::waitpid(-1, nullptr, WNOHANG) == -1 && errno == ECHILD; }

void ignore_answer(IsolatedReader&) {}
void read_two_values(IsolatedReader& r) {
    r.u64();
    r.u64();
}

// Runs `work` isolated with a receiver that expects two values, and returns the crash's message.
std::string crash_message(const std::function<void(IsolatedWriter&)>& work,
                          std::string* child_stderr = nullptr) {
    try {
        run_isolated(work, read_two_values);
    } catch (const IsolatedCrash& e) {
        if (child_stderr) *child_stderr = e.child_stderr();
        return e.what();
    }
    FAIL("the child's death was not reported");
    return "";
}

}  // namespace

TEST_CASE("isolated_call: values and a large payload cross intact") {
    // 4 MiB of doubles: far beyond a pipe's 64 KiB buffer, so the parent must read while the
    // child writes (a deadlock otherwise).
    constexpr std::size_t kCount = 1 << 19;
    std::vector<double> got;
    std::uint64_t n = 0;
    std::string text;
    double x = 0;
    run_isolated(
        [&](IsolatedWriter& w) {
            std::vector<double> v(kCount);
            for (std::size_t i = 0; i < kCount; ++i) v[i] = 0.5 * double(i) - 7.25;
            w.u64(kCount);
            w.str("make model");
            w.f64(-0.0);
            w.bytes(v.data(), v.size() * sizeof(double));
        },
        [&](IsolatedReader& r) {
            n = r.u64();
            text = r.str(64);
            x = r.f64();
            got.resize(static_cast<std::size_t>(n));
            r.bytes(got.data(), got.size() * sizeof(double));
        });
    REQUIRE(n == kCount);
    CHECK(text == "make model");
    CHECK(std::signbit(x));
    for (std::size_t i = 0; i < kCount; i += 4099) CHECK(got[i] == 0.5 * double(i) - 7.25);
    CHECK(got.back() == 0.5 * double(kCount - 1) - 7.25);
    CHECK(no_children_left());
}

TEST_CASE("isolated_call: an empty answer is an answer") {
    bool received = false;
    run_isolated([](IsolatedWriter&) {}, [&](IsolatedReader&) { received = true; });
    CHECK(received);
    CHECK(no_children_left());
}

TEST_CASE("isolated_call: the child's errors keep their class and message") {
    const auto throws = [](auto make) { return [make](IsolatedWriter&) { throw make(); }; };
    CHECK_THROWS_WITH_AS(
        run_isolated(throws([] { return ResourceLimit("too big: 5 GB"); }), ignore_answer),
        "too big: 5 GB", ResourceLimit);
    CHECK_THROWS_WITH_AS(
        run_isolated(throws([] { return InvalidInput("field: bad"); }), ignore_answer),
        "field: bad", InvalidInput);
    // An InvalidInput that is not a ResourceLimit stays one.
    try {
        run_isolated(throws([] { return InvalidInput("x"); }), ignore_answer);
    } catch (const ResourceLimit&) {
        FAIL("InvalidInput became ResourceLimit");
    } catch (const InvalidInput&) {
    }
    CHECK_THROWS_WITH_AS(
        run_isolated(throws([] { return RuntimeFailure("solver broke"); }), ignore_answer),
        "solver broke", RuntimeFailure);
    CHECK_THROWS_AS(run_isolated(throws([] { return std::bad_alloc(); }), ignore_answer),
                    std::bad_alloc);
    CHECK_THROWS_WITH_AS(
        run_isolated(throws([] { return std::out_of_range("index 9"); }), ignore_answer), "index 9",
        RuntimeFailure);
    // The receiver is not called when the child failed.
    bool received = false;
    CHECK_THROWS_AS(run_isolated(throws([] { return InvalidInput("x"); }),
                                 [&](IsolatedReader&) { received = true; }),
                    InvalidInput);
    CHECK_FALSE(received);
    CHECK(no_children_left());
}

TEST_CASE("isolated_call: every way a child dies is a crash, named, and the caller survives") {
    CHECK(crash_message([](IsolatedWriter&) { std::raise(SIGSEGV); }) ==
          "the child process was killed by signal 11 (Segmentation fault) before it had sent "
          "its whole answer");
    std::string err;
    const std::string aborted = crash_message(
        [](IsolatedWriter&) {
            std::fputs("*** buffer overflow detected ***: terminated\n", stderr);
            std::fflush(stderr);
            std::abort();
        },
        &err);
    CHECK(aborted ==
          "the child process was killed by signal 6 (Aborted) before it had sent its whole "
          "answer: *** buffer overflow detected ***: terminated");
    CHECK(err == "*** buffer overflow detected ***: terminated\n");
    CHECK(crash_message([](IsolatedWriter&) { ::_exit(86); }) ==
          "the child process exited with status 86 before it had sent its whole answer");
    // Dies half-way through its answer: the parent's read comes up short.
    CHECK(crash_message([](IsolatedWriter& w) {
              w.u64(1);
              ::_exit(0);
          }).find("exited with status 0 before it had sent its whole answer") != std::string::npos);
    // Throws after it started answering: nothing the parent could trust.
    CHECK(crash_message([](IsolatedWriter& w) {
              w.u64(1);
              throw InvalidInput("late");
          }).find("exited with status 3") != std::string::npos);
    // Dies after the whole answer (say, in a destructor): refused too.
    std::uint64_t v = 0;
    try {
        run_isolated(
            [](IsolatedWriter& w) {
                w.u64(42);
                std::raise(SIGSEGV);
            },
            [&](IsolatedReader& r) { v = r.u64(); });
        FAIL("a child killed after its answer was accepted");
    } catch (const IsolatedCrash& e) {
        CHECK(std::string(e.what()) ==
              "the child process was killed by signal 11 (Segmentation fault) after sending "
              "its answer");
    }
    CHECK(v == 42);
    CHECK(no_children_left());
}

TEST_CASE("isolated_call: a receiver's refusal ends the child and propagates") {
    // The child would write for ever; the receiver refuses after the first value.
    CHECK_THROWS_WITH_AS(run_isolated(
                             [](IsolatedWriter& w) {
                                 for (;;) w.u64(7);
                             },
                             [](IsolatedReader& r) {
                                 if (r.u64() == 7) throw ResourceLimit("refused by the parent");
                             }),
                         "refused by the parent", ResourceLimit);
    // A string longer than the receiver allows is refused before it is allocated.
    CHECK_THROWS_AS(run_isolated([](IsolatedWriter& w) { w.str(std::string(100, 'x')); },
                                 [](IsolatedReader& r) { r.str(99); }),
                    RuntimeFailure);
    // An answer longer than was read is a protocol error, not silently dropped.
    CHECK_THROWS_WITH_AS(run_isolated(
                             [](IsolatedWriter& w) {
                                 w.u64(1);
                                 w.u64(2);
                             },
                             [](IsolatedReader& r) { r.u64(); }),
                         "a child process sent more than was read", RuntimeFailure);
    CHECK(no_children_left());
}

TEST_CASE("isolated_call: a caller that ignores SIGCHLD still gets answers and crashes") {
    // With SIGCHLD ignored the system reaps children itself and waitpid ends with ECHILD.
    struct sigaction ignore {
    }, old{};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    REQUIRE(::sigaction(SIGCHLD, &ignore, &old) == 0);
    std::uint64_t v = 0;
    run_isolated([](IsolatedWriter& w) { w.u64(5); }, [&](IsolatedReader& r) { v = r.u64(); });
    CHECK(v == 5);
    CHECK(crash_message([](IsolatedWriter&) { std::abort(); }) ==
          "the child process ended with an unknown status (SIGCHLD ignored) before it had sent "
          "its whole answer");
    REQUIRE(::sigaction(SIGCHLD, &old, nullptr) == 0);
}
