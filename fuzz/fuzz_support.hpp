// Shared pieces of the libFuzzer targets. Contract of every target: a reader given arbitrary
// bytes either returns a value or throws InvalidInput (ResourceLimit included); any other
// exception escapes to libFuzzer and is reported as a crash, like a sanitizer report, a timeout
// or an allocation beyond -malloc_limit_mb.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

namespace pinmask::fuzz {

// Memory bound the targets run under (core/limits/resource_limits): small, so a reader that checks
// its declared sizes refuses them instead of allocating up to libFuzzer's -rss_limit_mb.
inline constexpr const char* kFuzzMemoryLimit = "256M";

inline void set_memory_limit() { ::setenv("PINMASK_MEMORY_LIMIT", kFuzzMemoryLimit, 1); }

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// A scratch file of this process (the readers under test take paths), rewritten per input.
inline const std::filesystem::path& scratch_path(const std::string& extension) {
    static const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("pinmask-fuzz-" + std::to_string(::getpid()) + extension);
    return path;
}

inline const std::filesystem::path& write_scratch(const std::uint8_t* data, std::size_t size,
                                                  const std::string& extension) {
    const auto& path = scratch_path(extension);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    return path;
}

// A broken invariant (not a rejected input): print it and abort so libFuzzer keeps the input.
[[noreturn]] inline void invariant_failed(const char* what) {
    std::fprintf(stderr, "pinmask fuzz: invariant broken: %s\n", what);
    std::abort();
}

}  // namespace pinmask::fuzz
