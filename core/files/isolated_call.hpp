// Runs a piece of work in a child process (fork) and streams its answer back through a pipe, so
// that a crash inside a third-party library on hostile input (a memory error caught by
// _FORTIFY_SOURCE, an abort, a segfault) refuses that input instead of ending the caller.
// core/image/raw_io runs LibRaw this way: Debian 12's LibRaw 0.20.2 aborts on, for example, a DNG
// whose make is "Hasselblad" and whose model is 63 characters long (fixed upstream in 2026).
//
// Protocol: the child runs `work` with an IsolatedWriter. If `work` throws before it writes
// anything, the error crosses to the parent with its class and message (InvalidInput,
// ResourceLimit, RuntimeFailure, std::bad_alloc; any other std::exception as RuntimeFailure); the
// parent's `receive` is not called. Once `work` writes, the parent's `receive` reads the same
// sequence of values as they arrive (no size limit from the pipe); the child must then finish
// normally. The child's standard error goes to a memory file, never to the caller's: the library
// prints nothing, and a crash's message quotes it. The child leaves with _exit (no atexit handlers,
// no stdio flush) and restores the default action of the fatal signals first, so that a sanitizer's
// or fuzzer's crash handler inherited from the parent does not report the child's crash as the
// caller's.
//
// A caller that ignores SIGCHLD (SIG_IGN) gets its answers too, but a child that dies after its
// whole answer cannot be told from one that exited normally then. POSIX only. Safe in a
// multithreaded caller as far as `work` uses only async-signal-safe functions or those glibc makes
// fork-safe (malloc, stdio); it should not use thread pools the parent started (FFTW's, OpenMP's).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "core/errors/error.hpp"

namespace pinmask {

// The child died before its whole answer was read, or after it (a non-zero exit status or a
// signal). what() says how and quotes the last line the child wrote to its standard error, e.g.
// "the child process was killed by signal 6 (Aborted) ...: *** buffer overflow detected ***:
// terminated"; child_stderr() holds the end of that output (at most 64 KiB: a sanitizer's report).
class IsolatedCrash : public RuntimeFailure {
  public:
    IsolatedCrash(const std::string& what, std::string child_stderr)
        : RuntimeFailure(what), child_stderr_(std::move(child_stderr)) {}
    const std::string& child_stderr() const { return child_stderr_; }

  private:
    std::string child_stderr_;
};

// The child's end of the pipe: values in the parent's byte order (same machine).
class IsolatedWriter {
  public:
    explicit IsolatedWriter(int fd) : fd_(fd) {}
    void bytes(const void* data, std::size_t n);
    void u64(std::uint64_t v) { bytes(&v, sizeof v); }
    void f64(double v) { bytes(&v, sizeof v); }
    void str(const std::string& s);
    bool started() const { return started_; }

  private:
    int fd_;
    bool started_ = false;
};

// The parent's end: each read blocks until the child has written that much; a short read (the
// child died) ends the call with IsolatedCrash.
class IsolatedReader {
  public:
    explicit IsolatedReader(int fd) : fd_(fd) {}
    void bytes(void* data, std::size_t n);
    std::uint64_t u64();
    double f64();
    // Refuses (RuntimeFailure) a length above max_length: the parent never trusts a size.
    std::string str(std::size_t max_length);

  private:
    int fd_;
};

// Runs work(writer) in a child process and receive(reader) in this one, concurrently. Returns
// once the child has exited with status 0 and `receive` has returned. Throws the child's error as
// described above, IsolatedCrash if the child dies, RuntimeFailure if no process or pipe can be
// made; if `receive` throws, the child is killed and reaped and the exception propagates.
void run_isolated(const std::function<void(IsolatedWriter&)>& work,
                  const std::function<void(IsolatedReader&)>& receive);

}  // namespace pinmask
