// A small binary codec for the messages ranks exchange (optimize/search/rank_comm.hpp): fixed-width
// little-endian integers, doubles as their IEEE-754 bits (exact, infinities and NaN included),
// length-prefixed strings. Not a file format: files are JSON codecs in io/.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include "optimize/search/rank_comm.hpp"

namespace pinmask {

class ByteWriter {
  public:
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    void i64(std::int64_t v) { u64(static_cast<std::uint64_t>(v)); }
    void f64(double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        u64(bits);
    }
    void str(const std::string& s) {
        u64(s.size());
        out_.insert(out_.end(), s.begin(), s.end());
    }
    const Bytes& bytes() const { return out_; }
    Bytes take() { return std::move(out_); }

  private:
    Bytes out_;
};

// Reads what ByteWriter wrote; RuntimeFailure on a short or over-long buffer (a corrupt message).
class ByteReader {
  public:
    explicit ByteReader(const Bytes& in) : in_(in) {}
    std::uint64_t u64();
    std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
    double f64() {
        const std::uint64_t bits = u64();
        double v;
        std::memcpy(&v, &bits, sizeof v);
        return v;
    }
    std::string str();
    // A count about to size a container: at most the bytes left divided by `min_item_bytes`.
    std::size_t count(std::size_t min_item_bytes);
    bool done() const { return pos_ == in_.size(); }
    void expect_done() const;

  private:
    const Bytes& in_;
    std::size_t pos_ = 0;
};

}  // namespace pinmask
