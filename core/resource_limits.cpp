#include "core/resource_limits.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.hpp"

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
    // Converting an infinite or too large double to size_t is undefined behaviour.
    if (!(v * scale < 0x1p64)) {
        throw invalid_field("PINMASK_MEMORY_LIMIT", text, "must be below 2^64 bytes");
    }
    return static_cast<std::size_t>(v * scale);
}

std::atomic<std::size_t> g_reserved{0};

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

}  // namespace pinmask
