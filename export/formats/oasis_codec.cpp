#include "export/formats/oasis_codec.hpp"

#include <cstring>

#include "core/errors/error.hpp"

namespace pinmask::oasis {
namespace {

// Coordinates beyond this are refused (pinmask's layouts stay within 2^30 nm; this bounds the
// arithmetic of repetitions and deltas with a wide margin).
constexpr std::uint64_t kMaxMagnitude = std::uint64_t{1} << 40;

InvalidInput bad(std::size_t at, const std::string& rule) {
    return InvalidInput("oasis: at byte " + std::to_string(at) + ": " + rule);
}

}  // namespace

std::string record_name(std::uint64_t id) {
    static const char* const names[] = {
        "PAD",        "START",     "END",        "CELLNAME",   "CELLNAME",   "TEXTSTRING",
        "TEXTSTRING", "PROPNAME",  "PROPNAME",   "PROPSTRING", "PROPSTRING", "LAYERNAME",
        "LAYERNAME",  "CELL",      "CELL",       "XYABSOLUTE", "XYRELATIVE", "PLACEMENT",
        "PLACEMENT",  "TEXT",      "RECTANGLE",  "POLYGON",    "PATH",       "TRAPEZOID",
        "TRAPEZOID",  "TRAPEZOID", "CTRAPEZOID", "CIRCLE",     "PROPERTY",   "PROPERTY",
        "XNAME",      "XNAME",     "XELEMENT",   "XGEOMETRY",  "CBLOCK"};
    return id < std::size(names) ? names[id] : "unknown";
}

void Writer::uint(std::uint64_t v) {
    do {
        std::uint8_t b = v & 0x7F;
        v >>= 7;
        if (v) b |= 0x80;
        byte(b);
    } while (v);
}

void Writer::sint(std::int64_t v) {
    const std::uint64_t m = v < 0 ? std::uint64_t(0) - std::uint64_t(v) : std::uint64_t(v);
    uint((m << 1) | (v < 0 ? 1 : 0));
}

void Writer::string(std::string_view s) {
    uint(s.size());
    raw(s);
}

void Writer::gdelta(std::int64_t dx, std::int64_t dy) {
    const std::uint64_t mx = dx < 0 ? std::uint64_t(0) - std::uint64_t(dx) : std::uint64_t(dx);
    uint((mx << 2) | (dx < 0 ? 2 : 0) | 1);
    sint(dy);
}

void Writer::end_record() {
    const std::size_t start = out_.size();
    byte(kEnd);
    // 1 (id) + 2 (length of the padding, >= 128) + padding + 1 (scheme 0) = 256
    const std::size_t pad = kEndRecordBytes - 4;
    uint(pad);
    out_.append(pad, '\0');
    uint(0);
    (void)start;
}

std::uint8_t Reader::byte() {
    if (pos_ >= b_.size()) throw bad(pos_, "file ends inside a record: truncated");
    return static_cast<std::uint8_t>(b_[pos_++]);
}

std::uint64_t Reader::uint() {
    const std::size_t at = pos_;
    std::uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
        if (shift > 63) throw bad(at, "integer longer than 64 bits");
        const std::uint8_t b = byte();
        if (shift == 63 && (b & 0x7E)) throw bad(at, "integer larger than 64 bits");
        v |= std::uint64_t(b & 0x7F) << shift;
        if (!(b & 0x80)) break;
    }
    return v;
}

std::int64_t Reader::sint() {
    const std::size_t at = pos_;
    const std::uint64_t u = uint();
    const std::uint64_t m = u >> 1;
    if (m > kMaxMagnitude) throw bad(at, "coordinate magnitude beyond 2^40");
    return (u & 1) ? -std::int64_t(m) : std::int64_t(m);
}

std::string_view Reader::string() {
    const std::size_t at = pos_;
    const std::uint64_t n = uint();
    if (n > b_.size() - pos_) throw bad(at, "string runs past the end: truncated");
    const std::string_view s = b_.substr(pos_, n);
    pos_ += n;
    return s;
}

void Reader::gdelta(std::int64_t& dx, std::int64_t& dy) {
    const std::size_t at = pos_;
    const std::uint64_t u = uint();
    if (u & 1) {
        const std::uint64_t m = u >> 2;
        if (m > kMaxMagnitude) throw bad(at, "delta magnitude beyond 2^40");
        dx = (u & 2) ? -std::int64_t(m) : std::int64_t(m);
        dy = sint();
        return;
    }
    const std::uint64_t m = u >> 4;
    if (m > kMaxMagnitude) throw bad(at, "delta magnitude beyond 2^40");
    const auto d = std::int64_t(m);
    static const int kDx[8] = {1, 0, -1, 0, 1, -1, -1, 1};
    static const int kDy[8] = {0, 1, 0, -1, 1, 1, -1, -1};
    const int dir = int((u >> 1) & 7);
    dx = kDx[dir] * d;
    dy = kDy[dir] * d;
}

double Reader::real() {
    const std::size_t at = pos_;
    const std::uint64_t type = uint();
    switch (type) {
        case 0:
        case 1: {
            const double v = double(uint());
            return type == 0 ? v : -v;
        }
        case 2:
        case 3: {
            const std::uint64_t d = uint();
            if (d == 0) throw bad(at, "reciprocal of zero");
            return (type == 2 ? 1.0 : -1.0) / double(d);
        }
        case 4:
        case 5: {
            const double n = double(uint());
            const std::uint64_t d = uint();
            if (d == 0) throw bad(at, "ratio with a zero denominator");
            return (type == 4 ? 1.0 : -1.0) * n / double(d);
        }
        case 6: {
            std::uint32_t u = 0;
            for (int i = 0; i < 4; ++i) u |= std::uint32_t(byte()) << (8 * i);
            float f;
            std::memcpy(&f, &u, 4);
            return f;
        }
        case 7: {
            std::uint64_t u = 0;
            for (int i = 0; i < 8; ++i) u |= std::uint64_t(byte()) << (8 * i);
            double d;
            std::memcpy(&d, &u, 8);
            return d;
        }
        default:
            throw bad(at, "unknown real type " + std::to_string(type));
    }
}

void Reader::skip(std::size_t n) {
    if (n > b_.size() - pos_) throw bad(pos_, "record runs past the end: truncated");
    pos_ += n;
}

}  // namespace pinmask::oasis
