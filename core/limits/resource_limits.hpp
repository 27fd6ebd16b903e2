// One process-wide memory budget. The bound is PINMASK_MEMORY_LIMIT (bytes, or with suffix
// K/M/G) when set, else half the machine's memory. Large allocations that live on (decoded
// images, big planes, layouts) hold a MemoryReservation for their lifetime; the reservations of
// the whole process add up, so two requests that each fit cannot together exceed the bound.
// check_memory() asks whether a working set fits beside everything reserved now; a request
// that does not is refused with ResourceLimit (exit 2) before allocating, both figures in the
// message. Code, libraries and small allocations (below kChargeThresholdBytes) are not
// charged: the bound governs the data, and tests allow a stated margin for the rest.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "core/errors/error.hpp"

namespace pinmask {

std::size_t memory_limit_bytes();

// Allocations smaller than this are not charged (Image, Plane): 4 MiB.
inline constexpr double kChargeThresholdBytes = 4.0 * 1024 * 1024;

// Bytes currently reserved by live MemoryReservation objects of this process.
std::size_t memory_reserved_bytes();

// A charge against the process-wide budget, released on destruction (move-only).
class MemoryReservation {
  public:
    MemoryReservation() = default;
    // Throws ResourceLimit when reserved + bytes > memory_limit_bytes(); `what` names the data.
    MemoryReservation(double bytes, const std::string& what);
    MemoryReservation(MemoryReservation&& other) noexcept;
    MemoryReservation& operator=(MemoryReservation&& other) noexcept;
    MemoryReservation(const MemoryReservation&) = delete;
    MemoryReservation& operator=(const MemoryReservation&) = delete;
    ~MemoryReservation();

    std::size_t bytes() const { return bytes_; }
    // Gives back all but `bytes` (no-op when already smaller).
    void shrink_to(double bytes);
    void release();

  private:
    std::size_t bytes_ = 0;
};

// Throws ResourceLimit("<what> needs X GiB, more than the memory bound Y GiB ...") when
// bytes + memory_reserved_bytes() > memory_limit_bytes(). `bytes` is computed by the caller in
// double to avoid overflow (NaN or negative counts as too large).
void check_memory(double bytes, const std::string& what);

// One process-wide time budget, off unless a face starts it: the command line reads
// PINMASK_TIME_LIMIT once, before any command, and starts the clock there (cli/main.cpp); the
// Python module never starts it (a long-lived interpreter has no "whole run" to bound). The
// budget applies only inside a TimeLimitScope, opened by the paths that honour it: `decode
// --batch` polls time_limit_spent() between captures (and keeps what it finished); `check`
// polls check_time_limit() between its stages and in the long loops of its library code (file
// readers, design-rule check), and writes nothing. The same loops run for export, which opens no
// scope, so its polls do nothing.
// The budget is spent. Not an input error: the command line exits 3 for it.
class TimeLimitSpent : public Error {
  public:
    using Error::Error;
};

// The budget's bounds: a limit shorter than a microsecond or longer than 1e7 s (116 days) is a
// mistake (a lost unit), not a budget.
inline constexpr double kMinTimeLimitS = 1e-6;
inline constexpr double kMaxTimeLimitS = 1e7;

// Parses a PINMASK_TIME_LIMIT value: a duration such as 90s, 500ms, 2m (or 2min), 1.5h, or plain
// seconds. Throws InvalidInput naming PINMASK_TIME_LIMIT for 0, negative, NaN, infinite, unknown
// units and values outside [kMinTimeLimitS, kMaxTimeLimitS].
double parse_time_limit_s(std::string_view text);

// PINMASK_TIME_LIMIT parsed (nullopt when unset: no budget). Reads the environment each call.
std::optional<double> time_limit_from_environment();

// Starts the process's budget: it is spent `seconds` from now. A later call replaces it.
void start_time_limit(double seconds);

// The budget started by start_time_limit, nullopt when none was started.
std::optional<double> time_limit_s();

// While one lives (on any thread), the started budget applies to this process's polls.
class TimeLimitScope {
  public:
    TimeLimitScope();
    ~TimeLimitScope();
    TimeLimitScope(const TimeLimitScope&) = delete;
    TimeLimitScope& operator=(const TimeLimitScope&) = delete;
};

// True once a started budget is spent inside a TimeLimitScope (false when none was started or
// no scope is open).
bool time_limit_spent();

// "the time limit PINMASK_TIME_LIMIT = 2 s was spent" (the started budget's value).
std::string time_limit_spent_text();

// Throws TimeLimitSpent ("the time limit PINMASK_TIME_LIMIT = 2 s was spent: <what>") once the
// budget is spent; a no-op when none was started or no scope is open. Cheap enough for inner loops
// (one clock read).
void check_time_limit(const std::string& what);

// check_time_limit() every 4096th call, for loops whose steps are too cheap to read the clock
// at each.
class TimeLimitPoll {
  public:
    explicit TimeLimitPoll(const char* what) : what_(what) {}
    void operator()() {
        if ((++count_ & 4095u) == 0) check_time_limit(what_);
    }

  private:
    const char* what_;
    unsigned count_ = 0;
};

}  // namespace pinmask
