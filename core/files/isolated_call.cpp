#include "core/files/isolated_call.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <new>

namespace pinmask {
namespace {

// The first byte of an answer.
constexpr char kAnswer = 'O';  // values follow, in the order `work` wrote them
constexpr char kError = 'E';   // an error class byte and its message follow
// Error classes.
constexpr char kInvalid = 'I', kResource = 'R', kRuntime = 'F', kNoMemory = 'M';
// The longest error message that crosses (a longer one is cut).
constexpr std::size_t kMaxMessage = 1 << 16;
// How much of the child's standard error is kept, and quoted in a crash's message.
constexpr std::size_t kMaxStderr = 1 << 16, kMaxQuotedLine = 200;
// Child exit statuses of its own (anything else came from the work or a signal).
constexpr int kFailedAfterAnswerStarted = 3, kPipeWriteFailed = 4;

// Thrown by IsolatedReader on a short read; run_isolated turns it into IsolatedCrash.
struct ShortAnswer {};

void write_all(int fd, const void* data, std::size_t n) {
    const char* p = static_cast<const char*>(data);
    while (n > 0) {
        const ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) ::_exit(kPipeWriteFailed);
        p += w;
        n -= static_cast<std::size_t>(w);
    }
}

// Bytes read before end of file (less than n only at the end).
std::size_t read_up_to(int fd, void* data, std::size_t n) {
    char* p = static_cast<char*>(data);
    std::size_t got = 0;
    while (got < n) {
        const ssize_t r = ::read(fd, p + got, n - got);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0)
            throw RuntimeFailure(std::string("reading a child process: ") + std::strerror(errno));
        if (r == 0) break;
        got += static_cast<std::size_t>(r);
    }
    return got;
}

// waitpid's status, or kStatusUnknown when the child was reaped by the system: a caller that
// ignores SIGCHLD (SIG_IGN) has its children reaped at exit, and waitpid then ends with ECHILD.
constexpr int kStatusUnknown = -1;

int wait_for(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return kStatusUnknown;
    }
    return status;
}

std::string describe(int status) {
    if (status == kStatusUnknown) return "ended with an unknown status (SIGCHLD ignored)";
    if (WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        const char* name = ::strsignal(sig);
        return "was killed by signal " + std::to_string(sig) + " (" + (name ? name : "unknown") +
               ")";
    }
    if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
    return "ended with wait status " + std::to_string(status);
}

// Sends the exception being handled, by class (the parent throws the same class).
void send_current_error(int fd) {
    char cls = kRuntime;
    std::string what = "unknown exception in a child process";
    try {
        throw;
    } catch (const ResourceLimit& e) {
        cls = kResource;
        what = e.what();
    } catch (const InvalidInput& e) {
        cls = kInvalid;
        what = e.what();
    } catch (const std::bad_alloc& e) {
        cls = kNoMemory;
        what = e.what();
    } catch (const std::exception& e) {
        what = e.what();
    } catch (...) {
    }
    if (what.size() > kMaxMessage) what.resize(kMaxMessage);
    const char head[2] = {kError, cls};
    write_all(fd, head, 2);
    const std::uint64_t len = what.size();
    write_all(fd, &len, sizeof len);
    write_all(fd, what.data(), what.size());
}

[[noreturn]] void run_child(int fd, const std::function<void(IsolatedWriter&)>& work) {
    // The default action for the fatal signals: the parent sees the signal, and no handler
    // inherited from it (a sanitizer's, a fuzzer's) reports this crash as the parent's.
    for (const int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS})
        std::signal(sig, SIG_DFL);
    IsolatedWriter writer(fd);
    try {
        work(writer);
        if (!writer.started()) writer.bytes(nullptr, 0);  // an empty answer
    } catch (...) {
        // Once values have gone out, an error frame would be read as values: die instead.
        if (writer.started()) ::_exit(kFailedAfterAnswerStarted);
        send_current_error(fd);
    }
    ::_exit(0);
}

// The end of what the child wrote to its standard error (a memory file): its last line names the
// failure (glibc's "*** buffer overflow detected ***", a sanitizer's summary).
std::string stderr_tail(int fd) {
    const off_t size = ::lseek(fd, 0, SEEK_END);
    if (size <= 0) return "";
    const off_t from = std::max<off_t>(0, size - static_cast<off_t>(kMaxStderr));
    std::string s(static_cast<std::size_t>(size - from), '\0');
    const ssize_t got = ::pread(fd, s.data(), s.size(), from);
    s.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
    return s;
}

std::string last_line(const std::string& text) {
    std::size_t end = text.find_last_not_of(" \t\r\n");
    if (end == std::string::npos) return "";
    const std::size_t newline = text.rfind('\n', end);
    const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
    std::string line = text.substr(begin, end - begin + 1);
    if (line.size() > kMaxQuotedLine) line = line.substr(0, kMaxQuotedLine) + "...";
    return line;
}

// Closes the read end and reaps the child on every way out of run_isolated.
// The standard error file stays open until the guard goes (a crash's message reads it).
class ChildGuard {
  public:
    ChildGuard(pid_t pid, int fd, int err_fd) : pid_(pid), fd_(fd), err_fd_(err_fd) {}
    ChildGuard(const ChildGuard&) = delete;
    ChildGuard& operator=(const ChildGuard&) = delete;
    ~ChildGuard() {
        if (pid_ >= 0) {
            ::kill(pid_, SIGKILL);
            ::close(fd_);
            wait_for(pid_);
        }
        ::close(err_fd_);
    }
    // Normal end: the pipe closed, then the exit status.
    int finish() {
        ::close(fd_);
        const int status = wait_for(pid_);
        pid_ = -1;
        return status;
    }

  private:
    pid_t pid_;
    int fd_, err_fd_;
};

}  // namespace

void IsolatedWriter::bytes(const void* data, std::size_t n) {
    if (!started_) {
        started_ = true;
        write_all(fd_, &kAnswer, 1);
    }
    if (n) write_all(fd_, data, n);
}

void IsolatedWriter::str(const std::string& s) {
    u64(s.size());
    bytes(s.data(), s.size());
}

void IsolatedReader::bytes(void* data, std::size_t n) {
    if (read_up_to(fd_, data, n) != n) throw ShortAnswer{};
}

std::uint64_t IsolatedReader::u64() {
    std::uint64_t v = 0;
    bytes(&v, sizeof v);
    return v;
}

double IsolatedReader::f64() {
    double v = 0;
    bytes(&v, sizeof v);
    return v;
}

std::string IsolatedReader::str(std::size_t max_length) {
    const std::uint64_t n = u64();
    if (n > max_length)
        throw RuntimeFailure("a child process sent a string of " + std::to_string(n) +
                             " bytes (at most " + std::to_string(max_length) + " expected)");
    std::string s(static_cast<std::size_t>(n), '\0');
    bytes(s.data(), s.size());
    return s;
}

void run_isolated(const std::function<void(IsolatedWriter&)>& work,
                  const std::function<void(IsolatedReader&)>& receive) {
    std::array<int, 2> fds{};
    if (::pipe2(fds.data(), O_CLOEXEC) != 0)
        throw RuntimeFailure(std::string("cannot make a pipe to a child process: ") +
                             std::strerror(errno));
    const int err_fd = ::memfd_create("pinmask-child-stderr", MFD_CLOEXEC);
    const pid_t pid = err_fd < 0 ? -1 : ::fork();
    if (pid < 0) {
        const int err = errno;
        ::close(fds[0]);
        ::close(fds[1]);
        if (err_fd >= 0) ::close(err_fd);
        throw RuntimeFailure(std::string("cannot start a child process: ") + std::strerror(err));
    }
    if (pid == 0) {
        ::close(fds[0]);
        if (::dup2(err_fd, STDERR_FILENO) < 0) ::_exit(kPipeWriteFailed);
        run_child(fds[1], work);
    }
    ::close(fds[1]);
    ChildGuard child(pid, fds[0], err_fd);
    IsolatedReader reader(fds[0]);
    const auto crash = [&](const std::string& how) {
        const std::string err = stderr_tail(err_fd);
        const std::string line = last_line(err);
        return IsolatedCrash("the child process " + how + (line.empty() ? "" : ": " + line), err);
    };
    char head = 0;
    try {
        if (read_up_to(fds[0], &head, 1) != 1) throw ShortAnswer{};
        if (head == kAnswer) {
            receive(reader);
            char extra = 0;
            if (read_up_to(fds[0], &extra, 1) != 0)
                throw RuntimeFailure("a child process sent more than was read");
            const int status = child.finish();
            // The whole answer arrived; with SIGCHLD ignored its exit status cannot be known.
            if (status != 0 && status != kStatusUnknown)
                throw crash(describe(status) + " after sending its answer");
            return;
        }
        if (head != kError) throw ShortAnswer{};
        char cls = 0;
        reader.bytes(&cls, 1);
        const std::string message = reader.str(kMaxMessage);
        child.finish();
        switch (cls) {
            case kResource:
                throw ResourceLimit(message);
            case kInvalid:
                throw InvalidInput(message);
            case kNoMemory:
                throw std::bad_alloc();
            default:
                throw RuntimeFailure(message);
        }
    } catch (const ShortAnswer&) {
        const int status = child.finish();
        throw crash(describe(status) + " before it had sent its whole answer");
    }
}

}  // namespace pinmask
