// Image files made by libtiff and libpng directly, in layouts our writers never produce:
// compression, tiles, separate planes, big-endian TIFF, extra (alpha) samples; PNG palette,
// sub-8-bit grey, alpha, interlacing; npy versions 2.0/3.0 and the integer dtypes.
// Expected values come from the generating formula, not from our writers.
#include <doctest/doctest.h>
#include <png.h>
#include <tiffio.h>

#include <csetjmp>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/image/image_io.hpp"
#include "tests/core/image_io_fixtures.hpp"

using namespace pinmask;
using namespace pinmask::test;
namespace fs = std::filesystem;

namespace {

// A 16-bit value per (row, col, sample) with every byte varying.
std::uint16_t pattern(int r, int c, int k) {
    return static_cast<std::uint16_t>((r * 257 + c * 31 + k * 1009 + r * c) % 65536);
}

struct RawTiff {
    int rows = 37, cols = 21, colour = 1, extra = 0;
    bool separate = false;
    int tile = 0;  // 0: strips of 3 rows
    std::uint16_t compression = COMPRESSION_NONE;
    const char* mode = "w";  // "wb": big-endian, "w8": BigTIFF
};

void write_raw_tiff(const fs::path& path, const RawTiff& s) {
    TIFF* t = TIFFOpen(path.c_str(), s.mode);
    REQUIRE(t != nullptr);
    const int spp = s.colour + s.extra;
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, std::uint32_t(s.cols));
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, std::uint32_t(s.rows));
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 16);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, spp);
    TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, s.colour == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, s.separate ? PLANARCONFIG_SEPARATE : PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_COMPRESSION, s.compression);
    if (s.extra) {
        const std::uint16_t types[1] = {EXTRASAMPLE_UNASSALPHA};
        TIFFSetField(t, TIFFTAG_EXTRASAMPLES, 1, types);
    }
    const int planes = s.separate ? spp : 1, stride = s.separate ? 1 : spp;
    if (s.tile) {
        TIFFSetField(t, TIFFTAG_TILEWIDTH, s.tile);
        TIFFSetField(t, TIFFTAG_TILELENGTH, s.tile);
        std::vector<std::uint16_t> buf(std::size_t(s.tile) * s.tile * stride);
        for (int pl = 0; pl < planes; ++pl)
            for (int y0 = 0; y0 < s.rows; y0 += s.tile)
                for (int x0 = 0; x0 < s.cols; x0 += s.tile) {
                    for (int i = 0; i < s.tile; ++i)
                        for (int j = 0; j < s.tile; ++j)
                            for (int k = 0; k < stride; ++k)
                                buf[(std::size_t(i) * s.tile + j) * stride + k] =
                                    pattern(y0 + i, x0 + j, s.separate ? pl : k);
                    REQUIRE(TIFFWriteTile(t, buf.data(), x0, y0, 0, pl) > 0);
                }
    } else {
        TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 3);
        std::vector<std::uint16_t> row(std::size_t(s.cols) * stride);
        for (int pl = 0; pl < planes; ++pl)
            for (int r = 0; r < s.rows; ++r) {
                for (int c = 0; c < s.cols; ++c)
                    for (int k = 0; k < stride; ++k)
                        row[std::size_t(c) * stride + k] = pattern(r, c, s.separate ? pl : k);
                REQUIRE(TIFFWriteScanline(t, row.data(), r, pl) >= 0);
            }
    }
    TIFFClose(t);
}

// Checks the loaded image has `colour` channels holding pattern(r, c, k).
void check_pattern(const LoadedImage& im, int rows, int cols, int colour) {
    REQUIRE(im.image.rows() == rows);
    REQUIRE(im.image.cols() == cols);
    REQUIRE(im.image.n_channels() == colour);
    CHECK(im.format == SampleFormat::kUint16);
    bool ok = true;
    for (int k = 0; k < colour; ++k)
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) ok &= im.image.channels[k](r, c) == pattern(r, c, k);
    CHECK(ok);
}

struct RawPng {
    int width = 0, height = 0, bit_depth = 8, color_type = PNG_COLOR_TYPE_GRAY;
    bool interlace = false;
    std::vector<png_color> palette;
    std::vector<png_byte> trns;
    std::vector<png_bytep> rows;  // into caller-owned packed row data
};

// libpng writer with its own setjmp: no object with a destructor lives in this frame.
bool write_raw_png_c(std::FILE* fp, const RawPng* s) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, fp);
    png_set_IHDR(png, info, s->width, s->height, s->bit_depth, s->color_type,
                 s->interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!s->palette.empty()) png_set_PLTE(png, info, s->palette.data(), int(s->palette.size()));
    if (!s->trns.empty()) png_set_tRNS(png, info, s->trns.data(), int(s->trns.size()), nullptr);
    png_write_info(png, info);
    png_write_image(png, const_cast<png_bytepp>(s->rows.data()));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

// Writes a PNG whose sample (r, c, k) is value(r, c, k), packed MSB-first for depths < 8 and
// big-endian for 16 bits; n_samples per pixel as the colour type implies.
void write_raw_png(const fs::path& path, RawPng s, int n_samples,
                   const std::function<unsigned(int, int, int)>& value) {
    const std::size_t row_bits = std::size_t(s.width) * n_samples * s.bit_depth;
    const std::size_t row_bytes = (row_bits + 7) / 8;
    std::vector<png_byte> data(row_bytes * s.height, 0);
    for (int r = 0; r < s.height; ++r) {
        png_byte* row = data.data() + r * row_bytes;
        for (int c = 0; c < s.width; ++c)
            for (int k = 0; k < n_samples; ++k) {
                const unsigned v = value(r, c, k);
                const std::size_t i = std::size_t(c) * n_samples + k;
                if (s.bit_depth == 16) {
                    row[2 * i] = png_byte(v >> 8);
                    row[2 * i + 1] = png_byte(v & 0xff);
                } else if (s.bit_depth == 8) {
                    row[i] = png_byte(v);
                } else {
                    const std::size_t bit = i * s.bit_depth;
                    row[bit / 8] |= png_byte(v << (8 - s.bit_depth - bit % 8));
                }
            }
        s.rows.push_back(row);
    }
    std::FILE* fp = std::fopen(path.c_str(), "wb");
    REQUIRE(fp != nullptr);
    const bool ok = write_raw_png_c(fp, &s);
    std::fclose(fp);
    REQUIRE(ok);
}

}  // namespace

TEST_CASE("TIFF layouts written by libtiff: compression, tiles, planes, byte order, alpha") {
    ScratchDir dir("io-tiffvar");
    struct V {
        const char* name;
        RawTiff spec;
    };
    std::vector<V> variants = {
        {"grey strips", {}},
        {"rgb separate planes", {.colour = 3, .separate = true}},
        {"rgb big-endian", {.colour = 3, .mode = "wb"}},
        {"bigtiff", {.mode = "w8"}},
        {"grey + alpha", {.extra = 1}},
        {"grey tiled 16", {.tile = 16}},
        {"rgba tiled separate", {.colour = 3, .extra = 1, .separate = true, .tile = 16}},
    };
    for (std::uint16_t comp : {COMPRESSION_LZW, COMPRESSION_ADOBE_DEFLATE, COMPRESSION_PACKBITS}) {
        if (!TIFFIsCODECConfigured(comp)) {
            MESSAGE("libtiff codec " << comp << " not configured: variant skipped");
            continue;
        }
        variants.push_back(
            {"compressed rgba strips", {.colour = 3, .extra = 1, .compression = comp}});
        variants.push_back({"compressed grey tiles", {.tile = 16, .compression = comp}});
    }
    for (const V& v : variants) {
        INFO(v.name << " compression " << v.spec.compression);
        const fs::path p = dir / "v.tif";
        write_raw_tiff(p, v.spec);
        const std::string magic = read_bytes(p).substr(0, 4);
        const std::string mode = v.spec.mode;
        CHECK(magic == std::string(mode == "wb" ? "MM\0*" : mode == "w8" ? "II+\0" : "II*\0", 4));
        check_pattern(read_image(p), v.spec.rows, v.spec.cols, v.spec.colour);
    }
}

TEST_CASE("PNG layouts written by libpng: palette, sub-8-bit grey, alpha, interlace") {
    ScratchDir dir("io-pngvar");
    const fs::path p = dir / "v.png";
    const int h = 13, w = 11;
    {  // palette with transparency expands to RGB, alpha dropped
        RawPng s{.width = w, .height = h, .color_type = PNG_COLOR_TYPE_PALETTE};
        s.palette = {{10, 20, 30}, {200, 100, 0}, {1, 2, 3}, {255, 255, 255}};
        s.trns = {0, 128};
        write_raw_png(p, s, 1, [](int r, int c, int) { return unsigned(r + c) % 4; });
        const LoadedImage im = read_image(p);
        REQUIRE(im.image.n_channels() == 3);
        CHECK(im.format == SampleFormat::kUint8);
        bool ok = true;
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                const png_color e = s.palette[(r + c) % 4];
                ok &= im.image.channels[0](r, c) == e.red &&
                      im.image.channels[1](r, c) == e.green && im.image.channels[2](r, c) == e.blue;
            }
        CHECK(ok);
    }
    for (int depth : {1, 2, 4}) {
        {  // sub-8-bit grey scales to 8 bits
            INFO("depth " << depth);
            RawPng s{.width = w, .height = h, .bit_depth = depth};
            const unsigned top = (1u << depth) - 1;
            write_raw_png(p, s, 1,
                          [&](int r, int c, int) { return unsigned(r * 3 + c) % (top + 1); });
            const LoadedImage im = read_image(p);
            REQUIRE(im.image.n_channels() == 1);
            CHECK(im.full_scale == 255.0);
            bool ok = true;
            for (int r = 0; r < h; ++r)
                for (int c = 0; c < w; ++c)
                    ok &=
                        im.image.channels[0](r, c) == double((r * 3 + c) % (top + 1)) * (255 / top);
            CHECK(ok);
        }
    }
    {  // grey + alpha keeps grey; RGBA 16 keeps RGB; Adam7 interlace
        RawPng ga{.width = w, .height = h, .color_type = PNG_COLOR_TYPE_GRAY_ALPHA};
        write_raw_png(p, ga, 2, [](int r, int c, int k) { return k ? 77u : unsigned(r * 19 + c); });
        LoadedImage im = read_image(p);
        REQUIRE(im.image.n_channels() == 1);
        bool ok = true;
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) ok &= im.image.channels[0](r, c) == r * 19 + c;
        CHECK(ok);
        for (bool interlace : {false, true}) {
            RawPng rgba{.width = w,
                        .height = h,
                        .bit_depth = 16,
                        .color_type = PNG_COLOR_TYPE_RGB_ALPHA,
                        .interlace = interlace};
            write_raw_png(p, rgba, 4, [](int r, int c, int k) { return pattern(r, c, k); });
            check_pattern(read_image(p), h, w, 3);
        }
    }
}

TEST_CASE("npy versions 2.0 and 3.0, shape (r, c, 1), dtypes '|u1' and '<u2'") {
    ScratchDir dir("io-npyvar");
    const fs::path p = dir / "v.npy";
    std::string u2, u1;
    for (int i = 0; i < 3 * 5; ++i) {
        u2 += char(pattern(i / 5, i % 5, 0) & 0xff);
        u2 += char(pattern(i / 5, i % 5, 0) >> 8);
        u1 += char(pattern(i / 5, i % 5, 0) & 0xff);
    }
    for (int major : {1, 2, 3}) {
        INFO("version " << major);
        write_bytes(
            p,
            npy_bytes(major, "{'descr': '<u2', 'fortran_order': False, 'shape': (3, 5, 1), }", u2));
        check_pattern(read_image(p), 3, 5, 1);
    }
    // Keys in another order, double quotes, no trailing comma: still a valid Python literal.
    write_bytes(
        p, npy_bytes(1, "{\"shape\": (3, 5), \"fortran_order\": False, \"descr\": \"|u1\"}", u1));
    const LoadedImage im = read_image(p);
    CHECK(im.format == SampleFormat::kUint8);
    CHECK(im.full_scale == 255.0);
    REQUIRE(im.image.n_channels() == 1);
    CHECK(im.image.channels[0](2, 4) == (pattern(2, 4, 0) & 0xff));
}
