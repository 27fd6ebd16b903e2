// Memory bound for large requests: anything whose working set would exceed it is refused with
// ResourceLimit (exit 2) before allocating, with the figure in the message. The bound is
// PINMASK_MEMORY_LIMIT (bytes, or with suffix K/M/G) when set, else half the machine's memory.
#pragma once

#include <cstddef>
#include <string>

namespace pinmask {

std::size_t memory_limit_bytes();

// Throws ResourceLimit("<what> needs X GiB, more than the memory bound Y GiB ...") when
// bytes > memory_limit_bytes(). `bytes` is computed by the caller in double to avoid overflow.
void check_memory(double bytes, const std::string& what);

}  // namespace pinmask
