#include "optimize/search/byte_codec.hpp"

#include "core/errors/error.hpp"

namespace pinmask {

std::uint64_t ByteReader::u64() {
    if (in_.size() - pos_ < 8) throw RuntimeFailure("corrupt message: truncated");
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(in_[pos_ + i]) << (8 * i);
    pos_ += 8;
    return v;
}

std::string ByteReader::str() {
    const std::size_t n = count(1);
    std::string s(in_.begin() + static_cast<std::ptrdiff_t>(pos_),
                  in_.begin() + static_cast<std::ptrdiff_t>(pos_ + n));
    pos_ += n;
    return s;
}

std::size_t ByteReader::count(std::size_t min_item_bytes) {
    const std::uint64_t n = u64();
    if (min_item_bytes == 0) min_item_bytes = 1;
    if (n > (in_.size() - pos_) / min_item_bytes) {
        throw RuntimeFailure("corrupt message: a count larger than the message");
    }
    return static_cast<std::size_t>(n);
}

void ByteReader::expect_done() const {
    if (!done()) throw RuntimeFailure("corrupt message: trailing bytes");
}

}  // namespace pinmask
