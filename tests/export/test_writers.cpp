#include <doctest/doctest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/errors/error.hpp"
#include "export/formats/dxf_writer.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/pdf_writer.hpp"
#include "export/formats/png_preview.hpp"
#include "export/formats/svg_writer.hpp"
#include "export/layout/geometry.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;

namespace {

const std::string kGoldenDir = std::string(PINMASK_SOURCE_DIR) + "/tests/export/golden/";

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Compares with the golden file; PINMASK_UPDATE_GOLDEN=1 rewrites it instead (then inspect the
// diff before committing).
void check_golden(const std::string& name, const std::string& bytes) {
    const std::string path = kGoldenDir + name;
    if (const char* u = std::getenv("PINMASK_UPDATE_GOLDEN"); u && std::string(u) == "1") {
        std::ofstream(path, std::ios::binary) << bytes;
        MESSAGE("updated " << path);
    }
    const std::string want = slurp(path);
    INFO("golden " << path << " (" << want.size() << " bytes, got " << bytes.size() << ")");
    CHECK(bytes == want);
}

std::uint64_t fnv1a(const std::string& s) {
    std::uint64_t h = 14695981039346656037ULL;
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ULL;
    }
    return h;
}

Layout busy_layout(bool mirror) {
    LayoutOptions o;
    o.shape = HoleShape::kCircle;
    o.chord_tolerance_m = 100e-9;
    o.tone = Tone::kDark;
    o.mirror = mirror;
    o.frame_m = 200e-6;
    o.marks = true;
    o.label_lines = default_label_lines(pinmask::test::golden_mask(), "busy");
    o.max_vertices = 40;
    return make_layout(pinmask::test::golden_mask(), o);
}

std::uint64_t be64(const std::string& s, std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
    return v;
}

}  // namespace

TEST_CASE("golden files of the 4 x 4 mask with 3 pinholes (text formats byte for byte)") {
    const Layout l = make_layout(pinmask::test::golden_mask(), {});
    check_golden("golden4x4.svg", svg_document(l));
    check_golden("golden4x4.dxf", dxf_document(l));
    check_golden("golden4x4.gbr", gerber_document(l));
    // Binary formats by hash (FNV-1a 64 of the bytes). The PDF hash pins Cairo 1.16's output.
    CHECK(fnv1a(gds_stream(l)) == 0xda5bbbfd81c35b6eULL);
    CHECK(fnv1a(pdf_document(l)) == 0xe6c7134c17e5b7e4ULL);
}

TEST_CASE("every writer is deterministic: the same layout gives the same bytes") {
    for (bool mirror : {false, true}) {
        const Layout a = busy_layout(mirror), b = busy_layout(mirror);
        CHECK(svg_document(a) == svg_document(b));
        CHECK(gds_stream(a) == gds_stream(b));
        CHECK(dxf_document(a) == dxf_document(b));
        CHECK(gerber_document(a) == gerber_document(b));
        CHECK(pdf_document(a) == pdf_document(b));
        CHECK(png_preview(a, 300) == png_preview(b, 300));
    }
    CHECK(svg_document(busy_layout(false)) != svg_document(busy_layout(true)));
}

TEST_CASE("GDSII 8-byte reals: published encodings and exact round trips of doubles") {
    // Excess-64 base-16: value = mantissa / 2^56 * 16^(exponent - 64).
    CHECK(gds_real8_bits(1.0) == 0x4110000000000000ULL);
    CHECK(gds_real8_bits(-1.0) == 0xC110000000000000ULL);
    CHECK(gds_real8_bits(0.5) == 0x4080000000000000ULL);
    CHECK(gds_real8_bits(10.0) == 0x41A0000000000000ULL);
    CHECK(gds_real8_bits(100.0) == 0x4264000000000000ULL);
    CHECK(gds_real8_bits(0.0) == 0ULL);
    // 1e-3 and 1e-9 rounded to nearest (files written by truncating end in ...EF and ...51).
    CHECK(gds_real8_bits(1e-3) == 0x3E4189374BC6A7F0ULL);
    CHECK(gds_real8_bits(1e-9) == 0x3944B82FA09B5A54ULL);
    CHECK(gds_real8_value(0x3E4189374BC6A7EFULL) == doctest::Approx(1e-3).epsilon(1e-15));
    CHECK(gds_real8_value(0x3944B82FA09B5A51ULL) == doctest::Approx(1e-9).epsilon(1e-15));
    // A normalised mantissa keeps >= 53 significant bits, so every double in range round-trips.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> expo(-60, 60), mant(-1, 1);
    for (int i = 0; i < 20000; ++i) {
        const double x = mant(rng) * std::pow(10.0, expo(rng));
        CHECK(gds_real8_value(gds_real8_bits(x)) == x);
    }
    CHECK_THROWS_AS(gds_real8_bits(1e80), InvalidInput);
    CHECK_THROWS_AS(gds_real8_bits(std::nan("")), InvalidInput);
}

TEST_CASE("GDSII stream structure: records, units, closed boundaries, pinned timestamps") {
    const Layout l = busy_layout(false);
    const std::string s = gds_stream(l, {.layer = 7, .datatype = 3});
    // Walk the records independently of the reader.
    std::size_t pos = 0, boundaries = 0;
    std::vector<int> types;
    while (pos < s.size()) {
        const std::size_t len = (std::size_t(static_cast<unsigned char>(s[pos])) << 8) |
                                static_cast<unsigned char>(s[pos + 1]);
        REQUIRE(len >= 4);
        const int type = static_cast<unsigned char>(s[pos + 2]);
        types.push_back(type);
        if (type == 0x00) CHECK(s.substr(pos, 6) == std::string("\x00\x06\x00\x02\x02\x58", 6));
        if (type == 0x01 || type == 0x05) {  // BGNLIB/BGNSTR: 2000-01-01 00:00:00 twice
            const char want[] = "\x07\xd0\x00\x01\x00\x01\x00\x00\x00\x00\x00\x00";
            CHECK(std::memcmp(s.data() + pos + 4, want, 12) == 0);
            CHECK(std::memcmp(s.data() + pos + 16, want, 12) == 0);
        }
        if (type == 0x03) {
            CHECK(be64(s, pos + 4) == gds_real8_bits(1e-3));
            CHECK(be64(s, pos + 12) == gds_real8_bits(1e-9));
        }
        if (type == 0x0D) CHECK(s[pos + 5] == 7);
        if (type == 0x0E) CHECK(s[pos + 5] == 3);
        if (type == 0x10 && len > 12) {  // boundary XY: first point repeated last
            ++boundaries;
            CHECK(s.substr(pos + 4, 8) == s.substr(pos + len - 8, 8));
            CHECK((len - 4) / 8 <= 8191);
        }
        pos += len;
    }
    CHECK(pos == s.size());
    CHECK(types.front() == 0x00);
    CHECK(types.back() == 0x04);
    CHECK(boundaries == l.polygons.size() + l.annotations.size());
    CHECK_THROWS_AS(gds_stream(l, {.layer = 40000}), InvalidInput);
}

TEST_CASE("text formats declare units, tone, mirroring and hash; polarity follows the tone") {
    const Layout dark = busy_layout(true);
    const Layout clear = make_layout(pinmask::test::golden_mask(), {});
    const std::string info = "hash=" + dark.mask_hash + " tone=dark drawn=opaque mirrored=yes";
    CHECK(svg_document(dark).find(info + " units=um grid_nm=1") != std::string::npos);
    CHECK(dxf_document(dark).find(info + " units=um grid_nm=1") != std::string::npos);
    CHECK(gerber_document(dark).find(info + " units=mm grid_nm=1") != std::string::npos);
    CHECK(gerber_document(dark).find("%TF.FilePolarity,Positive*%") != std::string::npos);
    CHECK(gerber_document(clear).find("%TF.FilePolarity,Negative*%") != std::string::npos);
    CHECK(gds_stream(dark).find(info + " units=nm") != std::string::npos);
    // SVG size: width/height in mm equal the extent, viewBox in um.
    const std::string svg = svg_document(clear);
    CHECK(svg.find("width=\"1.76mm\" height=\"1.76mm\" viewBox=\"-880 -880 1760 1760\"") !=
          std::string::npos);
    CHECK_THROWS_AS(dxf_document(clear, {.layer = "0"}), InvalidInput);
    CHECK_THROWS_AS(dxf_document(clear, {.layer = "bad name"}), InvalidInput);
    CHECK(dxf_document(clear, {.layer = "HOLES_1"}).find("\n  8\nHOLES_1\n") != std::string::npos);
}

TEST_CASE("PDF: pinned dates, metadata, page = extent + margin + title block at 1:1") {
    const Layout l = make_layout(pinmask::test::golden_mask(), {});
    const std::string pdf = pdf_document(l, {.margin_m = 5e-3});
    CHECK(pdf.starts_with("%PDF-1.5"));
    CHECK(pdf.find("/CreationDate (20000101000000Z)") != std::string::npos);
    CHECK(pdf.find("/ModDate (20000101000000Z)") != std::string::npos);
    CHECK(pdf.find("pinmask mask " + l.mask_hash) != std::string::npos);
    CHECK(scale_bar_nm(1760000) == 500000);
    CHECK(scale_bar_nm(10000000) == 5000000);
    CHECK(scale_bar_nm(1) == 1);
    CHECK_THROWS_AS(pdf_document(l, {.margin_m = -1}), InvalidInput);
}
