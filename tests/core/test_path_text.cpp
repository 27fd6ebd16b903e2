// core/files/path_text: invalid_utf8_at against a reference decoder written here another way
// (decode the code point from the leading byte's bit pattern, then reject overlong forms,
// surrogates and code points beyond U+10FFFF), over every 1- and 2-byte string and every
// 3- and 4-byte string built from the boundary bytes; printable_text escapes what it rejects.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/files/path_text.hpp"

namespace {

// Reference: the offset of the first invalid byte, or npos.
std::size_t reference_invalid_at(const std::string& s) {
    std::size_t i = 0;
    while (i < s.size()) {
        const auto c = static_cast<std::uint8_t>(s[i]);
        int len;
        std::uint32_t cp;
        if ((c & 0x80) == 0) {
            len = 1, cp = c;
        } else if ((c & 0xE0) == 0xC0) {
            len = 2, cp = c & 0x1F;
        } else if ((c & 0xF0) == 0xE0) {
            len = 3, cp = c & 0x0F;
        } else if ((c & 0xF8) == 0xF0) {
            len = 4, cp = c & 0x07;
        } else {
            return i;
        }
        if (i + len > s.size()) return i;
        for (int k = 1; k < len; ++k) {
            const auto d = static_cast<std::uint8_t>(s[i + k]);
            if ((d & 0xC0) != 0x80) return i;
            cp = (cp << 6) | (d & 0x3F);
        }
        const std::uint32_t min_cp[] = {0, 0, 0x80, 0x800, 0x10000};
        if (cp < min_cp[len] || (cp >= 0xD800 && cp <= 0xDFFF) || cp > 0x10FFFF) return i;
        i += len;
    }
    return std::string::npos;
}

}  // namespace

TEST_CASE("invalid_utf8_at agrees with a reference decoder") {
    std::vector<std::string> cases;
    for (int a = 0; a < 256; ++a) {
        cases.push_back(std::string(1, char(a)));
        for (int b = 0; b < 256; ++b) cases.push_back(std::string{char(a), char(b)});
    }
    const unsigned char edges[] = {0x00, 0x41, 0x7F, 0x80, 0x8F, 0x90, 0x9F,
                                   0xA0, 0xBF, 0xC0, 0xC2, 0xE0, 0xF4, 0xFF};
    for (int a = 0xC0; a < 256; ++a)
        for (unsigned char b : edges)
            for (unsigned char c : edges) {
                cases.push_back(std::string{char(a), char(b), char(c)});
                for (unsigned char d : edges)
                    cases.push_back(std::string{char(a), char(b), char(c), char(d)});
            }
    std::size_t invalid = 0, disagree = 0;
    for (const std::string& s : cases) {
        const std::size_t want = reference_invalid_at("ok/" + s + "/x");
        if (pinmask::invalid_utf8_at("ok/" + s + "/x") != want) {
            ++disagree;
            INFO("case of " << s.size() << " bytes, first "
                            << int(static_cast<unsigned char>(s[0])));
            CHECK(pinmask::invalid_utf8_at("ok/" + s + "/x") == want);
        }
        invalid += want != std::string::npos;
    }
    CHECK(disagree == 0);
    CHECK(invalid > cases.size() / 2);  // the cases reach both answers
    CHECK(pinmask::invalid_utf8_at("caf\xC3\xA9 \xF0\x9F\x93\xB7.tiff") == std::string::npos);
    CHECK(pinmask::invalid_utf8_at("\xED\xA0\x80") == 0);        // a surrogate
    CHECK(pinmask::invalid_utf8_at("a\xC0\xAF") == 1);           // an overlong '/'
    CHECK(pinmask::invalid_utf8_at("ab\xF4\x90\x80\x80") == 2);  // beyond U+10FFFF
}

TEST_CASE("printable_text keeps UTF-8 and escapes every other byte") {
    CHECK(pinmask::printable_text("caf\xC3\xA9.npy") == "caf\xC3\xA9.npy");
    CHECK(pinmask::printable_text("m\xFF\xFE.json") == "m\\xFF\\xFE.json");
    CHECK(pinmask::printable_text(std::string("a\0b", 3)) == "a\\x00b");
    CHECK(pinmask::printable_text("\xE2\x82") == "\\xE2\\x82");  // a cut sequence
}
