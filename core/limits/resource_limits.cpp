#include "core/limits/resource_limits.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"

namespace pinmask {
namespace {

std::size_t parse_limit(const char* text) {
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    double scale = 1.0;
    if (end && *end) {
        switch (*end) {
            case 'K':
            case 'k':
                scale = 1024.0;
                break;
            case 'M':
            case 'm':
                scale = 1024.0 * 1024.0;
                break;
            case 'G':
            case 'g':
                scale = 1024.0 * 1024.0 * 1024.0;
                break;
            default:
                throw invalid_field("PINMASK_MEMORY_LIMIT", text,
                                    "expected bytes, e.g. 8G or 512M");
        }
    }
    if (!(v > 0.0)) throw invalid_field("PINMASK_MEMORY_LIMIT", text, "must be > 0");
    // A fraction of a byte would be a bound of 0 bytes (0 itself is refused just above).
    if (!(v * scale >= 1.0)) {
        throw invalid_field("PINMASK_MEMORY_LIMIT", text,
                            "must be at least 1 byte (a size such as 512M or 8G)");
    }
    // Converting an infinite or too large double to size_t is undefined behaviour.
    if (!(v * scale < 0x1p64)) {
        throw invalid_field("PINMASK_MEMORY_LIMIT", text, "must be below 2^64 bytes");
    }
    return static_cast<std::size_t>(v * scale);
}

std::atomic<std::size_t> g_reserved{0};

using Clock = std::chrono::steady_clock;
// The budget in seconds (0: none started) and its end in steady-clock ticks, set once by the
// face before any work, read by every thread afterwards.
std::atomic<double> g_time_limit_s{0.0};
std::atomic<Clock::rep> g_deadline{0};
std::atomic<int> g_scopes{0};  // open TimeLimitScope objects

std::string seconds_text(double s) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g s", s);
    return buf;
}

std::string gib(double bytes) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / (1024.0 * 1024.0 * 1024.0));
    return buf;
}

}  // namespace

std::size_t memory_limit_bytes() {
    if (const char* env = std::getenv("PINMASK_MEMORY_LIMIT")) return parse_limit(env);
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page <= 0) return std::size_t{4} << 30;
    return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) / 2;
}

std::size_t memory_reserved_bytes() { return g_reserved.load(); }

void check_memory(double bytes, const std::string& what) {
    const double limit = static_cast<double>(memory_limit_bytes());
    const double reserved = static_cast<double>(memory_reserved_bytes());
    if (!(bytes >= 0.0) || bytes + reserved > limit) {
        std::string msg = what + " needs " + gib(bytes);
        if (reserved > 0.0) msg += " beside the " + gib(reserved) + " this run already holds";
        throw ResourceLimit(msg + ", more than the memory bound " + gib(limit) +
                            " (set PINMASK_MEMORY_LIMIT to change it)");
    }
}

MemoryReservation::MemoryReservation(double bytes, const std::string& what) {
    const double limit = static_cast<double>(memory_limit_bytes());
    if (!(bytes >= 0.0) || !(bytes < limit + 1.0)) check_memory(bytes, what);  // throws
    const auto want = static_cast<std::size_t>(bytes);
    std::size_t now = g_reserved.load();
    do {
        if (static_cast<double>(now) + static_cast<double>(want) > limit) {
            check_memory(bytes, what);  // throws with the figures
        }
    } while (!g_reserved.compare_exchange_weak(now, now + want));
    bytes_ = want;
}

MemoryReservation::MemoryReservation(MemoryReservation&& other) noexcept : bytes_(other.bytes_) {
    other.bytes_ = 0;
}

MemoryReservation& MemoryReservation::operator=(MemoryReservation&& other) noexcept {
    if (this != &other) {
        release();
        bytes_ = other.bytes_;
        other.bytes_ = 0;
    }
    return *this;
}

MemoryReservation::~MemoryReservation() { release(); }

void MemoryReservation::shrink_to(double bytes) {
    if (!(bytes >= 0.0)) bytes = 0.0;
    const auto keep = static_cast<std::size_t>(std::min(bytes, static_cast<double>(bytes_)));
    g_reserved -= bytes_ - keep;
    bytes_ = keep;
}

void MemoryReservation::release() {
    g_reserved -= bytes_;
    bytes_ = 0;
}

double parse_time_limit_s(std::string_view text) {
    constexpr const char* kField = "PINMASK_TIME_LIMIT";
    const std::string quoted = "'" + std::string(text) + "'";
    std::string t(text);
    while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.pop_back();
    // "2m" is two minutes here (as for coreutils `timeout 2m`); the shared duration parser
    // spells it "2min" ("m" is a metre to it).
    if (!t.empty() && t.back() == 'm' && (t.size() < 2 || t[t.size() - 2] != 'm')) t += "in";
    double s = 0.0;
    try {
        s = parse_duration_s(t, kField);  // refuses NaN, inf, overflow and unknown units
    } catch (const InvalidInput&) {
        throw invalid_field(kField, quoted,
                            "expected a duration such as 90s, 500ms, 2m, 1.5h or plain seconds "
                            "(unset it for no limit)");
    }
    if (!(s > 0.0)) throw invalid_field(kField, quoted, "must be > 0 (unset it for no limit)");
    if (s < kMinTimeLimitS || s > kMaxTimeLimitS)
        throw invalid_field(kField, quoted,
                            "must be between 1e-06 s and 1e+07 s (116 days); unset it for no "
                            "limit");
    return s;
}

std::optional<double> time_limit_from_environment() {
    const char* env = std::getenv("PINMASK_TIME_LIMIT");
    if (!env) return std::nullopt;
    return parse_time_limit_s(env);
}

void start_time_limit(double seconds) {
    if (!(seconds >= kMinTimeLimitS && seconds <= kMaxTimeLimitS))
        throw invalid_field("PINMASK_TIME_LIMIT", seconds_text(seconds),
                            "must be between 1e-06 s and 1e+07 s");
    const auto span =
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    g_deadline.store((Clock::now() + span).time_since_epoch().count());
    g_time_limit_s.store(seconds);
}

std::optional<double> time_limit_s() {
    const double s = g_time_limit_s.load();
    if (s > 0.0) return s;
    return std::nullopt;
}

TimeLimitScope::TimeLimitScope() { g_scopes.fetch_add(1); }
TimeLimitScope::~TimeLimitScope() { g_scopes.fetch_sub(1); }

bool time_limit_spent() {
    if (g_scopes.load(std::memory_order_relaxed) == 0 || !(g_time_limit_s.load() > 0.0))
        return false;
    return Clock::now().time_since_epoch().count() >= g_deadline.load();
}

std::string time_limit_spent_text() {
    return "the time limit PINMASK_TIME_LIMIT = " + seconds_text(g_time_limit_s.load()) +
           " was spent";
}

void check_time_limit(const std::string& what) {
    if (!time_limit_spent()) return;
    throw TimeLimitSpent(time_limit_spent_text() + ": " + what);
}

}  // namespace pinmask
