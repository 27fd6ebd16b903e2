// JPEG input (core/image/jpeg_io via read_image): files written here with libjpeg's compressor from
// known 8-bit samples read back within the quality-100 round-trip bound; progressive and
// arithmetic-coded files (the same quantised coefficients, another entropy coding) decode to
// exactly the baseline file's samples; hostile files are refused by name. Bit-exact agreement
// with an independent libjpeg reader (PIL) on real photographs is tests/python/test_jpeg.py.
#include <doctest/doctest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "tests/core/image_io_fixtures.hpp"
#include "tests/core/jpeg_writer.hpp"

using namespace pinmask;
using namespace pinmask::test;
namespace fs = std::filesystem;

namespace {

// Quality 100 quantises every DCT coefficient with step 1, so what is left is the rounding of
// the integer forward and inverse DCTs (ISLOW, 13-bit fixed point: about 1 count per plane) and,
// for colour, of the RGB -> YCbCr -> RGB conversions at 4:4:4: each of Y, Cb, Cr is rounded to
// 8 bits twice, and B = Y + 1.772 (Cb - 128) multiplies a chroma error by up to 1.772, so a
// count in Y plus 1.772 counts from Cb plus the final rounding makes about 4.
// Measured on uniform random samples: grey 1 count, RGB 4 counts (test "round trip" below).
constexpr double kQ100GreyMaxAbsCounts = 2.0;
constexpr double kQ100RgbMaxAbsCounts = 5.0;

std::vector<unsigned char> random_samples(int rows, int cols, int components, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> u(0, 255);
    std::vector<unsigned char> s(std::size_t(rows) * cols * components);
    for (auto& v : s) v = static_cast<unsigned char>(u(rng));
    return s;
}

// Largest |read - source| over every sample; the image must have the source's layout.
double max_abs_counts(const Image& im, const std::vector<unsigned char>& src, int components) {
    REQUIRE(im.n_channels() == components);
    double worst = 0.0;
    for (int r = 0; r < im.rows(); ++r) {
        for (int c = 0; c < im.cols(); ++c) {
            for (int k = 0; k < components; ++k) {
                const double s = src[(std::size_t(r) * im.cols() + c) * components + k];
                worst = std::max(worst, std::abs(im.channels[k](r, c) - s));
            }
        }
    }
    return worst;
}

bool identical(const Image& a, const Image& b) {
    if (a.n_channels() != b.n_channels() || a.rows() != b.rows() || a.cols() != b.cols()) {
        return false;
    }
    for (int k = 0; k < a.n_channels(); ++k) {
        if (!(a.channels[k] == b.channels[k]).all()) return false;
    }
    return true;
}

LoadedImage read_written(const ScratchDir& dir, const std::string& name, const std::string& b) {
    write_bytes(dir / name, b);
    return read_image(dir / name);
}

}  // namespace

TEST_CASE("JPEG round trip: quality 100 grey and RGB read back within the rounding bound") {
    ScratchDir dir("jpeg-round-trip");
    // Odd, prime and multiple-of-8 sizes: partial 8 x 8 blocks at the right and bottom edges.
    for (const auto& [rows_c, cols_c] : {std::pair{37, 53}, std::pair{16, 24}, std::pair{1, 1}}) {
        const int rows = rows_c, cols = cols_c;
        INFO(rows << " x " << cols);
        const auto grey = random_samples(rows, cols, 1, 11);
        JpegSpec g;
        g.input = JCS_GRAYSCALE;
        const LoadedImage gi = read_written(dir, "grey.jpg", encode_jpeg(grey, rows, cols, g));
        CHECK(gi.format == SampleFormat::kUint8);
        CHECK(gi.full_scale == 255.0);
        REQUIRE(gi.image.rows() == rows);
        REQUIRE(gi.image.cols() == cols);
        const double grey_err = max_abs_counts(gi.image, grey, 1);
        MESSAGE("grey q100 max abs error " << grey_err << " counts");
        CHECK(grey_err <= kQ100GreyMaxAbsCounts);

        const auto rgb = random_samples(rows, cols, 3, 12);
        const LoadedImage ci = read_written(dir, "rgb.jpg", encode_jpeg(rgb, rows, cols, {}));
        CHECK(ci.format == SampleFormat::kUint8);
        CHECK(ci.full_scale == 255.0);
        REQUIRE(ci.image.rows() == rows);
        REQUIRE(ci.image.cols() == cols);
        const double rgb_err = max_abs_counts(ci.image, rgb, 3);
        MESSAGE("RGB (YCbCr 4:4:4) q100 max abs error " << rgb_err << " counts");
        CHECK(rgb_err <= kQ100RgbMaxAbsCounts);

        // An RGB file (Adobe transform 0: no YCbCr) also comes back as RGB, within the DCT
        // rounding alone.
        JpegSpec raw_rgb;
        raw_rgb.file = JCS_RGB;
        const LoadedImage ri =
            read_written(dir, "stored-rgb.jpg", encode_jpeg(rgb, rows, cols, raw_rgb));
        CHECK(max_abs_counts(ri.image, rgb, 3) <= kQ100GreyMaxAbsCounts);
    }
}

TEST_CASE("progressive and arithmetic-coded JPEGs decode to exactly the baseline samples") {
    // The entropy coding is lossless: the same quantised coefficients, so the same ISLOW output,
    // bit for bit, whether the scans are sequential, progressive (spectral selection and
    // successive approximation) or arithmetic-coded, and at 4:2:0 (fancy upsampling) too.
    ScratchDir dir("jpeg-variants");
    const int rows = 41, cols = 29;
    const auto rgb = random_samples(rows, cols, 3, 21);
    for (const bool subsample : {false, true}) {
        for (const int quality : {100, 75}) {
            INFO("subsample " << subsample << ", quality " << quality);
            JpegSpec base;
            base.subsample = subsample;
            base.quality = quality;
            const Image ref =
                read_written(dir, "base.jpg", encode_jpeg(rgb, rows, cols, base)).image;
            JpegSpec prog = base, arith = base, both = base;
            prog.progressive = true;
            arith.arithmetic = true;
            both.progressive = both.arithmetic = true;
            for (const auto& [name, spec] :
                 {std::pair{"prog.jpg", prog}, std::pair{"arith.jpg", arith},
                  std::pair{"prog-arith.jpg", both}}) {
                const std::string file = name;
                INFO(file);
                const std::string bytes = encode_jpeg(rgb, rows, cols, spec);
                CHECK(bytes != encode_jpeg(rgb, rows, cols, base));  // really another coding
                CHECK(identical(read_written(dir, file, bytes).image, ref));
            }
        }
    }
}

TEST_CASE("truncated and corrupt JPEG files are refused, never padded") {
    ScratchDir dir("jpeg-bad");
    const int rows = 64, cols = 48;
    const auto rgb = random_samples(rows, cols, 3, 31);
    const std::string good = encode_jpeg(rgb, rows, cols, {});
    REQUIRE(read_written(dir, "good.jpg", good).image.rows() == rows);  // the writer works
    const std::size_t scan = scan_data_offset(good);
    REQUIRE(scan != std::string::npos);
    REQUIRE(scan < good.size() / 2);
    // Cut in the middle of the scan: libjpeg would fill the rest with grey; refused.
    expect_refused(dir, "cut.jpg", good.substr(0, (scan + good.size()) / 2), {"truncated"});
    JpegSpec prog;
    prog.progressive = true;
    const std::string progressive = encode_jpeg(rgb, rows, cols, prog);
    expect_refused(dir, "cut-progressive.jpg", progressive.substr(0, progressive.size() * 2 / 3),
                   {"truncated"});
    // Every scan present, the EOI marker missing.
    expect_refused(dir, "no-eoi.jpg", good.substr(0, good.size() - 2), {"JPEG"});
    // Cut inside the header, or nothing after the magic bytes.
    expect_refused(dir, "cut-header.jpg", good.substr(0, 40), {"JPEG"});
    expect_refused(dir, "magic-only.jpg", "\xff\xd8\xff", {"JPEG"});
    expect_refused(dir, "app0-only.jpg", "\xff\xd8\xff\xe0", {"JPEG"});
    // A marker segment whose length field is 1 (at least 2 counts the length itself).
    std::string bogus = good;
    bogus[4] = '\0';
    bogus[5] = '\x01';
    expect_refused(dir, "bogus-length.jpg", bogus, {"JPEG header"});
    // Entropy-coded data replaced by a restart marker where none is due.
    std::string early_marker = good;
    early_marker[scan + 10] = '\xff';
    early_marker[scan + 11] = '\xd3';
    expect_refused(dir, "corrupt-scan.jpg", early_marker, {"corrupt"});
}

TEST_CASE("oversized and unsupported JPEG files are refused by name") {
    ScratchDir dir("jpeg-unsupported");
    const auto rgb = random_samples(16, 16, 3, 41);
    const std::string good = encode_jpeg(rgb, 16, 16, {});
    const std::size_t sof = sof_offset(good);
    REQUIRE(sof != std::string::npos);
    // Declared 65000 x 65000 x 3 (the largest JPEG size): refused from the header, before
    // libjpeg allocates its buffers or we allocate the image.
    std::string huge = good;
    huge[sof + 5] = huge[sof + 7] = char(65000 >> 8);
    huge[sof + 6] = huge[sof + 8] = char(65000 & 0xff);
    expect_refused(dir, "huge.jpg", huge, {"65000 x 65000", "kMaxImageSamples"});
    // Precision 12 (this libjpeg decodes 8-bit samples only).
    std::string twelve = good;
    twelve[sof + 4] = 12;
    expect_refused(dir, "twelve.jpg", twelve, {"JPEG header", "precision 12"});
    // Lossless JPEG (SOF3).
    std::string lossless = good;
    lossless[sof + 1] = '\xc3';
    expect_refused(dir, "lossless.jpg", lossless, {"JPEG header", "0xc3"});
    // Zero height in the frame header.
    std::string empty = good;
    empty[sof + 5] = empty[sof + 6] = '\0';
    expect_refused(dir, "zero-height.jpg", empty, {"JPEG"});

    const auto cmyk = random_samples(16, 16, 4, 42);
    JpegSpec c;
    c.input = JCS_CMYK;
    expect_refused(dir, "cmyk.jpg", encode_jpeg(cmyk, 16, 16, c), {"CMYK", "RGB"});
    c.file = JCS_YCCK;
    expect_refused(dir, "ycck.jpg", encode_jpeg(cmyk, 16, 16, c), {"YCCK", "RGB"});
}

TEST_CASE("a progressive JPEG with more than kMaxJpegScans scans is refused") {
    // Each scan is a pass over the whole frame: a small file of many tiny scans with a large
    // declared frame would take minutes. 64 scans (one per DCT band) decode like the baseline;
    // 64 x 11 = 704 (ten successive-approximation refinements per band, a valid script) do not.
    ScratchDir dir("jpeg-scans");
    const auto grey = random_samples(16, 16, 1, 61);
    JpegSpec g;
    g.input = JCS_GRAYSCALE;
    const Image ref = read_written(dir, "base.jpg", encode_jpeg(grey, 16, 16, g)).image;
    JpegSpec bands = g;
    bands.scans = single_band_script(0);
    CHECK(identical(read_written(dir, "bands.jpg", encode_jpeg(grey, 16, 16, bands)).image, ref));
    JpegSpec many = g;
    many.scans = single_band_script(10);
    REQUIRE(many.scans.size() == 704);
    expect_refused(dir, "many-scans.jpg", encode_jpeg(grey, 16, 16, many),
                   {"more than 500 scans", "kMaxJpegScans"});
}

TEST_CASE("a JPEG named like another format is read by its content") {
    ScratchDir dir("jpeg-by-content");
    const auto grey = random_samples(9, 7, 1, 51);
    JpegSpec g;
    g.input = JCS_GRAYSCALE;
    const std::string bytes = encode_jpeg(grey, 9, 7, g);
    const LoadedImage a = read_written(dir, "photo.jpg", bytes);
    const LoadedImage b = read_written(dir, "photo.png", bytes);
    CHECK(identical(a.image, b.image));
    CHECK(a.image.n_channels() == 1);
}
