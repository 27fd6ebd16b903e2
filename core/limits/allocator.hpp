// How the process's allocator keeps freed memory: the executables (the pinmask command, the
// Python module) call this once at start; the libraries never change process-wide state.
//
// Why: glibc's malloc returns freed memory to the system when the heap's free top exceeds its
// trim threshold (128 KiB, raised only to twice the largest mmap'd block freed so far) and serves
// blocks above its mmap threshold with fresh mappings. A decode allocates and frees planes of a
// few hundred KiB per call (spectra, filters, the estimate), so every call page-faulted its
// memory in again: measured in one process, a warm 128 x 128 Wiener decode_plane took 575 us
// with the defaults and 200 us with blocks up to 4 MiB kept on the heap and up to 32 MiB of free
// top kept (tests/decode, 2048 x 2448 period check and search evaluations allocate alike).
// Blocks above the mmap threshold still get their own mappings, returned on free, so a large
// decode's peak is not held afterwards; at most trim_threshold bytes of freed heap stay mapped.
#pragma once

#include <cstddef>

namespace pinmask {

inline constexpr std::size_t kKeptBlockBytes = std::size_t{4} << 20;     // mmap threshold
inline constexpr std::size_t kKeptFreeTopBytes = std::size_t{32} << 20;  // trim threshold

// Applies kKeptBlockBytes and kKeptFreeTopBytes (glibc mallopt; elsewhere nothing). Returns
// false when the allocator is not glibc's or refused a setting. The environment variable
// PINMASK_ALLOCATOR=default skips it (the allocator's own defaults; returns false).
bool keep_freed_memory();

}  // namespace pinmask
