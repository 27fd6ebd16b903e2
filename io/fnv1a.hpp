// FNV-1a 64 of a byte string as 16 lower-case hex digits: the checksum the export sidecar gives
// each file and a search checkpoint gives itself. It finds edits and corruption, not a forger
// (anyone can recompute it), so what it covers is validated field by field as well.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace pinmask::io {

inline std::string fnv1a64_hex(std::string_view bytes) {
    std::uint64_t h = 14695981039346656037ULL;
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

}  // namespace pinmask::io
