// NumPy .npy codec (format versions 1.0, 2.0, 3.0). Reads dtype '<f4', '<f8' (as is) and '|u1',
// '<u1', '<u2' (raw counts, full scale 255 / 65535); C order; shape (rows, cols),
// (rows, cols, 1) or (rows, cols, 3), channel last. The header dict is parsed strictly: exactly
// the keys 'descr', 'fortran_order', 'shape', Python literal syntax, at most kMaxNpyHeaderBytes,
// ending in '\n'; the data must be exactly the declared size. Writes version 1.0 with the header
// padded with spaces so the data starts at a multiple of 64 bytes, as numpy does.
// Sample bytes are encoded little-endian explicitly, independent of the host.
#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors/name_table.hpp"
#include "core/files/atomic_file.hpp"
#include "core/image/image_io.hpp"
#include "core/image/image_io_detail.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

// Bound on the header dict length; numpy's own reader refuses more than 10000 by default.
constexpr std::uint32_t kMaxNpyHeaderBytes = 1u << 16;
// Bound on the digits of one shape entry: 12 digits (< 10^12) cannot overflow the product test.
constexpr std::size_t kMaxShapeDigits = 12;
// Alignment of the data start used by numpy's writer.
constexpr std::size_t kNpyAlign = 64;

struct NpyHeader {
    std::string descr;
    bool fortran_order = false;
    std::vector<long long> shape;
};

// Strict parser for the header dict, e.g. "{'descr': '<f4', 'fortran_order': False,
// 'shape': (3, 4), }". Every error names the position and what was expected.
class HeaderParser {
  public:
    HeaderParser(std::string_view text, const fs::path& path) : s_(text), path_(path) {}

    NpyHeader parse() {
        NpyHeader h;
        bool seen_descr = false, seen_fortran = false, seen_shape = false;
        skip_ws();
        expect('{');
        for (;;) {
            skip_ws();
            if (peek() == '}') break;
            const std::string key = parse_string("a quoted key");
            skip_ws();
            expect(':');
            skip_ws();
            if (key == "descr") {
                if (seen_descr) fail("duplicate key 'descr'");
                h.descr = parse_string("a quoted dtype string for 'descr'");
                seen_descr = true;
            } else if (key == "fortran_order") {
                if (seen_fortran) fail("duplicate key 'fortran_order'");
                h.fortran_order = parse_bool();
                seen_fortran = true;
            } else if (key == "shape") {
                if (seen_shape) fail("duplicate key 'shape'");
                h.shape = parse_tuple();
                seen_shape = true;
            } else {
                fail("unknown key '" + key + "'");
            }
            skip_ws();
            if (peek() == ',') {
                ++i_;
                continue;
            }
            if (peek() != '}') fail("expected ',' or '}'");
        }
        expect('}');
        while (i_ < s_.size() && s_[i_] == ' ') ++i_;
        if (i_ + 1 != s_.size() || s_[i_] != '\n') {
            fail("expected only space padding and a final newline after the dict");
        }
        if (!seen_descr || !seen_fortran || !seen_shape) {
            fail("missing key(s): needs 'descr', 'fortran_order' and 'shape'");
        }
        return h;
    }

  private:
    [[noreturn]] void fail(const std::string& what) const {
        throw detail::bad_image_file(
            path_, "malformed npy header at byte " + std::to_string(i_) + ": " + what);
    }
    char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
    void skip_ws() {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
    }
    void expect(char c) {
        if (peek() != c) fail(std::string("expected '") + c + "'");
        ++i_;
    }
    bool match(std::string_view word) {
        if (s_.substr(i_, word.size()) != word) return false;
        i_ += word.size();
        return true;
    }
    std::string parse_string(const char* what) {
        const char q = peek();
        if (q != '\'' && q != '"') fail(std::string("expected ") + what);
        const std::size_t end = s_.find(q, i_ + 1);
        if (end == std::string_view::npos) fail("unterminated string");
        std::string out(s_.substr(i_ + 1, end - i_ - 1));
        for (const char c : out) {
            if (c == '\\' || c == '\n' || !std::isprint(static_cast<unsigned char>(c))) {
                fail("unsupported character in string");
            }
        }
        i_ = end + 1;
        return out;
    }
    bool parse_bool() {
        if (match("True")) return true;
        if (match("False")) return false;
        fail("expected True or False for 'fortran_order'");
    }
    std::vector<long long> parse_tuple() {
        std::vector<long long> dims;
        expect('(');
        for (;;) {
            skip_ws();
            if (peek() == ')') break;
            if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("expected a shape entry");
            const std::size_t start = i_;
            long long v = 0;
            while (std::isdigit(static_cast<unsigned char>(peek()))) {
                if (i_ - start >= kMaxShapeDigits) fail("shape entry too large");
                v = v * 10 + (s_[i_++] - '0');
            }
            if (peek() == 'L') ++i_;  // Python 2 long literal, written by old numpy
            dims.push_back(v);
            skip_ws();
            if (peek() == ',') {
                ++i_;
                continue;
            }
            if (peek() != ')') fail("expected ',' or ')' in shape");
        }
        expect(')');
        return dims;
    }

    std::string_view s_;
    const fs::path& path_;
    std::size_t i_ = 0;
};

SampleFormat parse_descr(const fs::path& path, const std::string& d) {
    if (d == "<f4") return SampleFormat::kFloat32;
    if (d == "<f8") return SampleFormat::kFloat64;
    if (d == "|u1" || d == "<u1") return SampleFormat::kUint8;
    if (d == "<u2") return SampleFormat::kUint16;
    if (d == ">f4" || d == ">f8" || d == ">u2") {
        throw detail::bad_image_file(path, "npy dtype '" + d +
                                               "' is big-endian: only little-endian data is "
                                               "supported (save with dtype '<" +
                                               d.substr(1) + "')");
    }
    throw detail::bad_image_file(path, "npy dtype '" + d +
                                           "' is not supported: expected '<f4', '<f8', '|u1' "
                                           "or '<u2'");
}

std::uint64_t load_le(const unsigned char* p, int bytes) {
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}

void store_le(unsigned char* p, std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}

double decode_le(const unsigned char* p, SampleFormat f) {
    switch (f) {
        case SampleFormat::kUint8:
            return p[0];
        case SampleFormat::kUint16:
            return double(load_le(p, 2));
        case SampleFormat::kFloat32:
            return std::bit_cast<float>(static_cast<std::uint32_t>(load_le(p, 4)));
        default:
            return std::bit_cast<double>(load_le(p, 8));
    }
}

void encode_le(unsigned char* p, SampleFormat f, double v) {
    switch (f) {
        case SampleFormat::kUint8:
            p[0] = static_cast<unsigned char>(detail::quantise(v, 255.0));
            break;
        case SampleFormat::kUint16:
            store_le(p, detail::quantise(v, 65535.0), 2);
            break;
        case SampleFormat::kFloat32:
            store_le(p, std::bit_cast<std::uint32_t>(static_cast<float>(v)), 4);
            break;
        default:
            store_le(p, std::bit_cast<std::uint64_t>(v), 8);
    }
}

const char* descr_of(SampleFormat f) {
    static constexpr NameTable<SampleFormat, 4> kDescr{{{SampleFormat::kUint8, "|u1"},
                                                        {SampleFormat::kUint16, "<u2"},
                                                        {SampleFormat::kFloat32, "<f4"},
                                                        {SampleFormat::kFloat64, "<f8"}}};
    return name_or(kDescr, f, "<f8");
}

}  // namespace

namespace detail {

LoadedImage read_npy(const fs::path& path) {
    std::error_code ec;
    const std::uintmax_t file_size = fs::file_size(path, ec);
    if (ec) throw bad_image_file(path, "cannot determine the file size");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw bad_image_file(path, "cannot be opened for reading");
    unsigned char pre[12] = {};
    in.read(reinterpret_cast<char*>(pre), 8);
    if (in.gcount() != 8) throw bad_image_file(path, "npy preamble truncated");
    const int major = pre[6], minor = pre[7];
    if ((major != 1 && major != 2 && major != 3) || minor != 0) {
        throw bad_image_file(path, "npy format version " + std::to_string(major) + "." +
                                       std::to_string(minor) +
                                       " is not supported: expected 1.0, 2.0 or 3.0");
    }
    const int len_bytes = major == 1 ? 2 : 4;
    in.read(reinterpret_cast<char*>(pre + 8), len_bytes);
    if (in.gcount() != len_bytes) throw bad_image_file(path, "npy header length truncated");
    const auto header_len = static_cast<std::uint32_t>(load_le(pre + 8, len_bytes));
    if (header_len > kMaxNpyHeaderBytes) {
        throw bad_image_file(path, "npy header length " + std::to_string(header_len) +
                                       " exceeds the limit of " +
                                       std::to_string(kMaxNpyHeaderBytes) + " bytes");
    }
    const std::uintmax_t data_offset = 8u + len_bytes + header_len;
    if (file_size < data_offset) {
        throw bad_image_file(path, "npy header truncated: declares " + std::to_string(header_len) +
                                       " bytes, file has " + std::to_string(file_size) +
                                       " bytes in total");
    }
    std::string text(header_len, '\0');
    in.read(text.data(), header_len);
    if (in.gcount() != std::streamsize(header_len))
        throw bad_image_file(path, "npy header truncated");

    const NpyHeader h = HeaderParser(text, path).parse();
    const SampleFormat format = parse_descr(path, h.descr);
    if (h.fortran_order) {
        throw bad_image_file(path,
                             "npy fortran_order is True: only C-order (row-major) arrays are "
                             "supported (save with np.ascontiguousarray)");
    }
    std::string shape_text = "(";
    for (std::size_t i = 0; i < h.shape.size(); ++i) {
        shape_text += (i ? ", " : "") + std::to_string(h.shape[i]);
    }
    shape_text += ")";
    const bool shape_ok =
        h.shape.size() == 2 || (h.shape.size() == 3 && (h.shape[2] == 1 || h.shape[2] == 3));
    if (!shape_ok) {
        throw bad_image_file(path, "npy shape " + shape_text +
                                       " is not supported: expected (rows, cols), (rows, cols, 1) "
                                       "or (rows, cols, 3)");
    }
    const long long rows = h.shape[0], cols = h.shape[1];
    const int n_ch = h.shape.size() == 3 ? int(h.shape[2]) : 1;
    const int bytes = bytes_of(format);
    const MemoryReservation decode_buffers =
        check_image_size(path, rows, cols, n_ch, double(rows) * cols * n_ch * bytes);
    const std::uintmax_t data_bytes = std::uintmax_t(rows) * cols * n_ch * bytes;
    if (file_size - data_offset != data_bytes) {
        throw bad_image_file(
            path,
            "npy data is " + std::to_string(file_size - data_offset) + " bytes but shape " +
                shape_text + " of " + h.descr + " needs " + std::to_string(data_bytes) +
                (file_size - data_offset < data_bytes ? " (truncated)" : " (trailing bytes)"));
    }
    std::vector<unsigned char> data(data_bytes);
    in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data_bytes));
    if (in.gcount() != std::streamsize(data_bytes))
        throw bad_image_file(path, "npy data truncated");

    LoadedImage out;
    out.image = Image(int(rows), int(cols), n_ch);
    out.format = format;
    out.full_scale = full_scale_of(format);
    const unsigned char* p = data.data();
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            for (int k = 0; k < n_ch; ++k, p += bytes)
                out.image.channels[k](r, c) = decode_le(p, format);
        }
    }
    return out;
}

}  // namespace detail

void write_npy(const fs::path& path, const Image& image, SampleFormat format) {
    detail::check_writable(path, image, format);
    const int rows = image.rows(), cols = image.cols(), n_ch = image.n_channels();
    std::string dict = std::string("{'descr': '") + descr_of(format) +
                       "', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                       std::to_string(cols) + (n_ch == 3 ? ", 3" : "") + "), }";
    const std::size_t unpadded = 10 + dict.size() + 1;  // preamble + dict + '\n'
    dict.append((kNpyAlign - unpadded % kNpyAlign) % kNpyAlign, ' ');
    dict += '\n';
    const int bytes = detail::bytes_of(format);
    std::string out;
    out.reserve(10 + dict.size() + std::size_t(rows) * cols * n_ch * bytes);
    out.append("\x93NUMPY\x01\x00", 8);
    out += static_cast<char>(dict.size() & 0xff);
    out += static_cast<char>(dict.size() >> 8);
    out += dict;
    const std::size_t data_start = out.size();
    out.resize(data_start + std::size_t(rows) * cols * n_ch * bytes);
    auto* p = reinterpret_cast<unsigned char*>(out.data() + data_start);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            for (int k = 0; k < n_ch; ++k, p += bytes)
                encode_le(p, format, image.channels[k](r, c));
        }
    }
    write_bytes_atomic(path, out);
}

}  // namespace pinmask
