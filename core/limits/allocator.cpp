#include "core/limits/allocator.hpp"

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace pinmask {

bool keep_freed_memory() {
    if (const char* env = std::getenv("PINMASK_ALLOCATOR"); env && std::strcmp(env, "default") == 0)
        return false;
#if defined(__GLIBC__)
    // mallopt returns 1 on success. Setting either threshold also turns off glibc's dynamic
    // adjustment of both, so the values stay as set.
    const bool mmap_ok = mallopt(M_MMAP_THRESHOLD, static_cast<int>(kKeptBlockBytes)) == 1;
    const bool trim_ok = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kKeptFreeTopBytes)) == 1;
    return mmap_ok && trim_ok;
#else
    return false;
#endif
}

}  // namespace pinmask
