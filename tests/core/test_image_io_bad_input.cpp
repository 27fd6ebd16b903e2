// Bad image files and bad write requests: every one is refused with InvalidInput (or
// ResourceLimit, RuntimeFailure where stated) whose message names the file and the problem,
// without a crash and without leaving files behind.
#include <doctest/doctest.h>
#include <tiffio.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/image/image_io.hpp"
#include "tests/core/image_io_fixtures.hpp"

using namespace pinmask;
using namespace pinmask::test;
namespace fs = std::filesystem;

namespace {

void put16(std::string& s, unsigned v) {
    s += char(v & 0xff);
    s += char((v >> 8) & 0xff);
}
void put32(std::string& s, std::uint32_t v) {
    put16(s, v & 0xffff);
    put16(s, v >> 16);
}

// A little-endian baseline TIFF built byte by byte: header, one IFD right after it, then one strip
// holding `data`, whose declared length is `declared_bytes`.
std::string crafted_tiff(std::uint32_t width, std::uint32_t height, unsigned bps,
                         unsigned photometric, std::uint32_t declared_bytes,
                         const std::string& data) {
    struct Entry {
        unsigned tag, type;
        std::uint32_t value;
    };
    constexpr unsigned kShort = 3, kLong = 4;
    const std::uint32_t n = 9, data_offset = 8 + 2 + n * 12 + 4;
    const Entry entries[] = {
        {256, kLong, width}, {257, kLong, height},       {258, kShort, bps},
        {259, kShort, 1},    {262, kShort, photometric}, {273, kLong, data_offset},
        {277, kShort, 1},    {278, kLong, height},       {279, kLong, declared_bytes}};
    std::string s = "II*";
    s += '\0';
    put32(s, 8);
    put16(s, n);
    for (const Entry& e : entries) {
        put16(s, e.tag);
        put16(s, e.type);
        put32(s, 1);
        put32(s, e.value);  // a SHORT sits in the low two bytes (little-endian)
    }
    put32(s, 0);
    return s + data;
}

std::string npy(const std::string& dict, const std::string& data = "") {
    return npy_bytes(1, dict, data);
}

}  // namespace

TEST_CASE("missing, empty and unrecognised files are refused by name") {
    ScratchDir dir("io-bad-any");
    const std::string missing = read_error(dir / "missing.tif");
    CHECK(contains(missing, "missing.tif"));
    CHECK(contains(missing, "does not exist"));
    expect_refused(dir, "empty.png", "", {"empty"});
    expect_refused(dir, "text.tif", "hello world, not an image", {"magic", "68 65 6c 6c"});
    expect_refused(dir, "short.tif", "II*", {"magic"});
    expect_refused(dir, "gif.png", "GIF89a", {"magic", "47 49 46"});
}

TEST_CASE("truncated, oversized and unsupported TIFF files are refused") {
    ScratchDir dir("io-bad-tiff");
    write_tiff(dir / "good.tif", random_image(31, 17, 3, 0, 1, 5), SampleFormat::kFloat32);
    const std::string good = read_bytes(dir / "good.tif");
    // Our writer puts the directory after the data: cutting the file loses the directory.
    expect_refused(dir, "cut.tif", good.substr(0, good.size() * 6 / 10), {"TIFF"});
    expect_refused(dir, "cut-header.tif", good.substr(0, 6), {"TIFF"});
    // Directory intact, strip shorter than declared.
    expect_refused(dir, "short-strip.tif", crafted_tiff(8, 8, 8, 1, 64, std::string(10, 'x')),
                   {"truncated"});
    const std::string ok = crafted_tiff(8, 8, 8, 1, 64, std::string(64, '\x07'));
    write_bytes(dir / "crafted.tif", ok);
    CHECK((read_image(dir / "crafted.tif").image.channels[0] == 7.0).all());  // the builder works
    expect_refused(dir, "huge.tif", crafted_tiff(100000, 100000, 8, 1, 0xfffffff0u, ""),
                   {"100000 x 100000", "kMaxImageSamples"});
    expect_refused(dir, "twelve.tif", crafted_tiff(8, 8, 12, 1, 96, std::string(96, 'x')),
                   {"12-bit", "supported"});
    {  // A palette TIFF needs a colour map (libtiff treats one without as grey): use libtiff.
        TIFF* t = TIFFOpen((dir / "palette.tif").c_str(), "w");
        REQUIRE(t != nullptr);
        std::vector<std::uint16_t> map(256, 0);
        TIFFSetField(t, TIFFTAG_IMAGEWIDTH, 8);
        TIFFSetField(t, TIFFTAG_IMAGELENGTH, 8);
        TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
        TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
        TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_PALETTE);
        TIFFSetField(t, TIFFTAG_COLORMAP, map.data(), map.data(), map.data());
        const std::vector<unsigned char> row(8, 1);
        for (int r = 0; r < 8; ++r)
            TIFFWriteScanline(t, const_cast<unsigned char*>(row.data()), r, 0);
        TIFFClose(t);
        const std::string msg = read_error(dir / "palette.tif");
        CHECK(contains(msg, "Palette"));
    }
    expect_refused(dir, "white.tif", crafted_tiff(8, 8, 8, 0, 64, std::string(64, 'x')),
                   {"MinIsWhite"});
}

TEST_CASE("truncated and corrupt PNG files are refused") {
    ScratchDir dir("io-bad-png");
    write_png(dir / "good.png", random_image(31, 17, 3, 0, 1, 6), 16);
    const std::string good = read_bytes(dir / "good.png");
    expect_refused(dir, "cut.png", good.substr(0, good.size() / 2), {"truncated or corrupt"});
    expect_refused(dir, "cut-header.png", good.substr(0, 20), {"PNG header"});
    expect_refused(dir, "no-iend.png", good.substr(0, good.size() - 12), {"PNG"});
    std::string flipped = good;
    const std::size_t idat = flipped.find("IDAT");
    REQUIRE(idat != std::string::npos);
    flipped[idat + 20] = char(flipped[idat + 20] ^ 0x5a);  // breaks the chunk CRC
    expect_refused(dir, "crc.png", flipped, {"PNG"});
}

TEST_CASE("npy: bounds, layouts, dtypes and malformed headers are refused by name") {
    ScratchDir dir("io-bad-npy");
    const std::string f4 = "{'descr': '<f4', 'fortran_order': False, 'shape': ";
    expect_refused(dir, "huge.npy", npy(f4 + "(100000, 100000), }"),
                   {"100000 x 100000", "kMaxImageSamples"});
    expect_refused(
        dir, "fortran.npy",
        npy("{'descr': '<f4', 'fortran_order': True, 'shape': (2, 2), }", std::string(16, '\0')),
        {"fortran_order"});
    expect_refused(
        dir, "big.npy",
        npy("{'descr': '>f4', 'fortran_order': False, 'shape': (2, 2), }", std::string(16, '\0')),
        {"big-endian", "'>f4'"});
    expect_refused(
        dir, "int.npy",
        npy("{'descr': '<i4', 'fortran_order': False, 'shape': (2, 2), }", std::string(16, '\0')),
        {"'<i4'", "not supported"});
    expect_refused(dir, "short.npy", npy(f4 + "(3, 5), }", std::string(10, '\0')), {"truncated"});
    expect_refused(dir, "long.npy", npy(f4 + "(1, 1), }", std::string(8, '\0')), {"trailing"});
    expect_refused(dir, "vector.npy", npy(f4 + "(5,), }", std::string(20, '\0')), {"shape (5)"});
    expect_refused(dir, "twochan.npy", npy(f4 + "(3, 4, 2), }", std::string(96, '\0')),
                   {"shape (3, 4, 2)"});
    expect_refused(dir, "zero.npy", npy(f4 + "(0, 4), }"), {"empty"});
    expect_refused(dir, "nodata-magic.npy", "\x93NUMPY", {"preamble truncated"});
    expect_refused(dir, "v4.npy", std::string("\x93NUMPY\x04\x00", 8) + "xxxx", {"version 4.0"});
    expect_refused(dir, "hlen.npy", std::string("\x93NUMPY\x02\x00\xff\xff\xff\xff", 12),
                   {"exceeds the limit"});
    expect_refused(dir, "hcut.npy", std::string("\x93NUMPY\x01\x00\x60\xea", 10) + "{'descr'",
                   {"header truncated"});
    // Malformed dicts: the parser names the problem.
    const std::pair<const char*, const char*> dicts[] = {
        {"{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2), ", "expected a quoted key"},
        {"{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2), 'x': 1}", "unknown key 'x'"},
        {"{'descr': '<f4', 'descr': '<f4', 'fortran_order': False, 'shape': (2, 2)}",
         "duplicate key 'descr'"},
        {"{'descr': '<f4', 'shape': (2, 2)}", "missing key"},
        {"{'descr': [('a', '<f4')], 'fortran_order': False, 'shape': (2, 2)}", "'descr'"},
        {"{'descr': '<f4', 'fortran_order': 0, 'shape': (2, 2)}", "True or False"},
        {"{'descr': '<f4', 'fortran_order': False, 'shape': (99999999999999999999, 1)}",
         "too large"},
        {"{'descr': '<f4', 'fortran_order': False, 'shape': (2, -2)}", "shape entry"},
        {"{'descr': '<f4 , 'fortran_order': False, 'shape': (2, 2)}", "malformed npy header"},
        {"{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2)} junk", "padding"},
    };
    int i = 0;
    for (const auto& [dict, needle] : dicts) {
        expect_refused(dir, "dict" + std::to_string(i++) + ".npy", npy(dict, std::string(16, '\0')),
                       {needle});
    }
    std::string no_newline = npy(f4 + "(2, 2), }", std::string(16, '\0'));
    no_newline[no_newline.size() - 17] = ' ';  // the header's final '\n'
    expect_refused(dir, "newline.npy", no_newline, {"final newline"});
}

TEST_CASE("the memory bound is applied from the declared size, before reading data") {
    ScratchDir dir("io-bad-mem");
    const fs::path p = dir / "big.npy";
    // 2000 x 2000 doubles = 32 MB: below kMaxImageSamples, above a 1 MiB bound.
    write_bytes(p, npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2000, 2000), }"));
    const char* old = std::getenv("PINMASK_MEMORY_LIMIT");
    const std::string saved = old ? old : "";
    ::setenv("PINMASK_MEMORY_LIMIT", "1M", 1);
    std::string msg;
    try {
        (void)read_image(p);
    } catch (const ResourceLimit& e) {
        msg = e.what();
    } catch (...) {
    }
    if (old) {
        ::setenv("PINMASK_MEMORY_LIMIT", saved.c_str(), 1);
    } else {
        ::unsetenv("PINMASK_MEMORY_LIMIT");
    }
    INFO(msg);
    CHECK(contains(msg, "big.npy"));
    CHECK(contains(msg, "memory bound"));
}

TEST_CASE("bad write requests are refused and leave no file") {
    ScratchDir dir("io-bad-write");
    const Image good = random_image(4, 6, 1, 0, 1, 9);
    Image two(4, 6, 2);
    Image nan = good;
    nan.channels[0](2, 3) = std::numeric_limits<double>::quiet_NaN();
    const auto refused = [&](const std::string& name, const std::function<void(const fs::path&)>& w,
                             const char* needle) {
        INFO(name);
        try {
            w(dir / name);
            FAIL_CHECK("write accepted");
        } catch (const InvalidInput& e) {
            CHECK(contains(e.what(), needle));
        }
        CHECK(!fs::exists(dir / name));
    };
    refused(
        "e.tif", [&](const fs::path& p) { write_tiff(p, Image(), SampleFormat::kFloat32); },
        "empty");
    refused(
        "two.png", [&](const fs::path& p) { write_png(p, two, 8); }, "2 channels");
    refused(
        "nan.tif", [&](const fs::path& p) { write_tiff(p, nan, SampleFormat::kUint16); }, "NaN");
    refused(
        "nan.png", [&](const fs::path& p) { write_png(p, nan, 16); }, "NaN");
    refused(
        "nan.npy", [&](const fs::path& p) { write_npy(p, nan, SampleFormat::kUint8); }, "NaN");
    refused(
        "twelve.png", [&](const fs::path& p) { write_png(p, good, 12); }, "8 or 16");
    // NaN is data in a float file: written and read back.
    write_tiff(dir / "nan32.tif", nan, SampleFormat::kFloat32);
    CHECK(std::isnan(read_image(dir / "nan32.tif").image.channels[0](2, 3)));
    // A directory that does not exist: a runtime failure, nothing created.
    for (const char* name : {"a.tif", "a.png", "a.npy"}) {
        const fs::path p = dir / "no-such-dir" / name;
        CHECK_THROWS_AS(write_image(p, good), RuntimeFailure);
        CHECK(!fs::exists(p.parent_path()));
    }
    int n_files = 0;
    for (const auto& e : fs::directory_iterator(dir.path())) n_files += e.is_regular_file();
    CHECK(n_files == 1);  // only nan32.tif
}
