// OASIS (SEMI P39) primitives shared by export/formats/oasis_writer and
// export/formats/oasis_reader: record ids, info-byte bits, and the integer, string and g-delta
// encodings.
//   unsigned integer: 7-bit groups, least significant first, high bit = more bytes follow;
//   signed integer:   the unsigned form of (|v| << 1) | sign;
//   string:           unsigned length, then the bytes;
//   g-delta:          form 1 (bit 0 = 0): (magnitude << 4) | (direction << 1), direction one of
//                     E N W S NE NW SW SE; form 2 (bit 0 = 1): (|dx| << 2) | (sign << 1) | 1,
//                     then dy as a signed integer.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace pinmask::oasis {

inline constexpr std::string_view kMagic = "%SEMI-OASIS\r\n";

enum Record : std::uint8_t {
    kPad = 0,
    kStart = 1,
    kEnd = 2,
    kCellNameImplicit = 3,
    kCellNameExplicit = 4,
    kTextStringImplicit = 5,
    kTextStringExplicit = 6,
    kCellByRef = 13,
    kCellByName = 14,
    kXyAbsolute = 15,
    kXyRelative = 16,
    kText = 19,
    kRectangle = 20,
    kPolygon = 21,
    kCblock = 34,
};

// Info-byte bits of RECTANGLE (SWHXYRDL), POLYGON (00PXYRDL) and TEXT (0CNXYRTL).
inline constexpr std::uint8_t kS = 0x80, kW = 0x40, kH = 0x20, kP = 0x20, kX = 0x10, kY = 0x08,
                              kR = 0x04, kD = 0x02, kL = 0x01;
inline constexpr std::uint8_t kTextExplicit = 0x40, kTextRef = 0x20, kTextType = 0x02,
                              kTextLayer = 0x01;
inline constexpr std::uint64_t kPointListGeneral = 4;
inline constexpr std::size_t kEndRecordBytes = 256;

// "RECTANGLE", "PLACEMENT", ... for messages (record ids 0..34; "unknown" beyond).
std::string record_name(std::uint64_t id);

class Writer {
  public:
    void byte(std::uint8_t b) { out_.push_back(char(b)); }
    void raw(std::string_view s) { out_ += s; }
    void uint(std::uint64_t v);
    void sint(std::int64_t v);
    void string(std::string_view s);
    void gdelta(std::int64_t dx, std::int64_t dy);  // always the second (general) form
    // END record: padding to 256 bytes, validation scheme 0 (none).
    void end_record();
    std::string& bytes() { return out_; }

  private:
    std::string out_;
};

// Reads primitives; every malformed or truncated value throws InvalidInput naming the offset.
class Reader {
  public:
    explicit Reader(std::string_view b) : b_(b) {}
    bool at_end() const { return pos_ >= b_.size(); }
    std::size_t offset() const { return pos_; }
    std::uint8_t byte();
    std::uint64_t uint();
    std::int64_t sint();
    std::string_view string();
    void gdelta(std::int64_t& dx, std::int64_t& dy);
    double real();  // types 0..5 (whole, reciprocal, ratio); 6, 7 (IEEE) too
    void skip(std::size_t n);

  private:
    std::string_view b_;
    std::size_t pos_ = 0;
};

}  // namespace pinmask::oasis
