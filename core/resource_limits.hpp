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
#include <string>

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

}  // namespace pinmask
