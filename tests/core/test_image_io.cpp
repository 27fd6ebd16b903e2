// Image file I/O: round trips of every format x depth x channel count, quantisation, format
// choice by extension, deterministic bytes, numpy's header layout, and the real sample files.
// Files made by libtiff/libpng directly (compression, tiles, planes, palette, alpha) are in
// test_image_io_variants.cpp; bad inputs in test_image_io_bad_input.cpp.
#include <doctest/doctest.h>
#include <tiffio.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <vector>

#include "core/image/image_io.hpp"
#include "tests/core/image_io_fixtures.hpp"

using namespace pinmask;
using namespace pinmask::test;
namespace fs = std::filesystem;

namespace {

// Float32 storage rounds to nearest: relative error at most half an ulp, 2^-24.
constexpr double kFloat32RelTol = 0x1p-24;
// Integer storage rounds v * full_scale to nearest: error at most half a count, plus the double
// round-off of v * full_scale / full_scale (a few ulps of 1).
constexpr double kHalfCount = 0.5;
constexpr double kDoubleSlack = 1e-12;

struct Case {
    const char* name;
    std::string ext;
    std::function<void(const fs::path&, const Image&)> write;
    SampleFormat format;
    double full_scale;
};

std::vector<Case> all_cases() {
    using F = SampleFormat;
    const auto tiff = [](F f) {
        return [f](const fs::path& p, const Image& im) { write_tiff(p, im, f); };
    };
    const auto npy = [](F f) {
        return [f](const fs::path& p, const Image& im) { write_npy(p, im, f); };
    };
    const auto png = [](int b) {
        return [b](const fs::path& p, const Image& im) { write_png(p, im, b); };
    };
    return {
        {"tiff uint8", ".tif", tiff(F::kUint8), F::kUint8, 255},
        {"tiff uint16", ".tif", tiff(F::kUint16), F::kUint16, 65535},
        {"tiff float32", ".tif", tiff(F::kFloat32), F::kFloat32, 1},
        {"tiff float64", ".tif", tiff(F::kFloat64), F::kFloat64, 1},
        {"png 8", ".png", png(8), F::kUint8, 255},
        {"png 16", ".png", png(16), F::kUint16, 65535},
        {"npy uint8", ".npy", npy(F::kUint8), F::kUint8, 255},
        {"npy uint16", ".npy", npy(F::kUint16), F::kUint16, 65535},
        {"npy float32", ".npy", npy(F::kFloat32), F::kFloat32, 1},
        {"npy float64", ".npy", npy(F::kFloat64), F::kFloat64, 1},
    };
}

bool is_integer_format(SampleFormat f) {
    return f == SampleFormat::kUint8 || f == SampleFormat::kUint16;
}

}  // namespace

TEST_CASE("every format x depth x {1, 3} channels round-trips at odd, prime and 2^k sizes") {
    ScratchDir dir("io-roundtrip");
    const int sizes[][2] = {{7, 5}, {1, 1}, {31, 17}, {16, 32}, {2, 1}};
    std::uint64_t seed = 1;
    for (const Case& fc : all_cases()) {
        for (const auto& sz : sizes) {
            for (int ch : {1, 3}) {
                const bool integer = is_integer_format(fc.format);
                // Integer formats take [0, 1]; float formats any value, negatives included.
                const Image in = integer ? random_image(sz[0], sz[1], ch, 0.0, 1.0, seed++)
                                         : random_image(sz[0], sz[1], ch, -1e3, 1e3, seed++);
                const fs::path p = dir / ("img" + fc.ext);
                fc.write(p, in);
                const LoadedImage out = read_image(p);
                INFO(fc.name << " " << sz[0] << "x" << sz[1] << "x" << ch);
                REQUIRE(out.image.rows() == sz[0]);
                REQUIRE(out.image.cols() == sz[1]);
                REQUIRE(out.image.n_channels() == ch);
                CHECK(out.format == fc.format);
                CHECK(out.full_scale == fc.full_scale);
                double worst = 0.0;
                bool counts_ok = true;
                for (int k = 0; k < ch; ++k) {
                    const Plane& a = out.image.channels[k];
                    const Plane& b = in.channels[k];
                    for (Eigen::Index i = 0; i < a.size(); ++i) {
                        const double x = a.data()[i], v = b.data()[i];
                        if (integer) {
                            counts_ok &= x == std::round(x) && x >= 0 && x <= fc.full_scale;
                            worst =
                                std::max(worst, std::fabs(x / fc.full_scale - v) * fc.full_scale);
                        } else if (fc.format == SampleFormat::kFloat32) {
                            worst = std::max(worst, std::fabs(x - v) / std::fabs(v));
                        } else {
                            worst = std::max(worst, x == v ? 0.0 : 1.0);  // float64: exact
                        }
                    }
                }
                CHECK(counts_ok);
                if (integer) {
                    CHECK(worst <= kHalfCount + kDoubleSlack * fc.full_scale);
                } else if (fc.format == SampleFormat::kFloat32) {
                    CHECK(worst <= kFloat32RelTol);
                } else {
                    CHECK(worst == 0.0);
                }
            }
        }
    }
}

TEST_CASE("integer writers clamp to [0, 1], round to nearest and store k / full_scale exactly") {
    ScratchDir dir("io-quant");
    for (const Case& fc : all_cases()) {
        if (!is_integer_format(fc.format)) continue;
        INFO(fc.name);
        const int n = fc.format == SampleFormat::kUint8 ? 16 : 256;  // n*n = 256 or 65536 counts
        Image in(n, n + 2, 1);
        Plane& p = in.channels[0];
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) p(r, c) = (r * n + c) / fc.full_scale;
        for (int r = 0; r < n; ++r) {
            p(r, n) = -0.5 - r;     // clamps to 0
            p(r, n + 1) = 1.5 + r;  // clamps to full scale
        }
        p(0, n + 1) = 2.4999 / fc.full_scale;  // rounds down to 2
        p(1, n + 1) = 2.5001 / fc.full_scale;  // rounds up to 3
        const fs::path path = dir / ("q" + fc.ext);
        fc.write(path, in);
        const Plane q = read_image(path).image.channels[0];
        bool exact = true;
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) exact &= q(r, c) == r * n + c;
        CHECK(exact);
        CHECK((q.col(n) == 0.0).all());
        CHECK((q.col(n + 1).tail(n - 2) == fc.full_scale).all());
        CHECK(q(0, n + 1) == 2.0);
        CHECK(q(1, n + 1) == 3.0);
    }
}

TEST_CASE("write_image chooses the format from the extension, case-insensitively") {
    ScratchDir dir("io-ext");
    const Image im = random_image(5, 7, 1, 0.0, 1.0, 42);
    const std::pair<const char*, SampleFormat> expect[] = {{"a.tif", SampleFormat::kFloat32},
                                                           {"b.TIFF", SampleFormat::kFloat32},
                                                           {"c.png", SampleFormat::kUint16},
                                                           {"d.npy", SampleFormat::kFloat32}};
    for (const auto& [name, format] : expect) {
        write_image(dir / name, im);
        CHECK(read_image(dir / name).format == format);
    }
    for (const char* name : {"e.bmp", "f"}) {
        INFO(name);
        try {
            write_image(dir / name, im);
            FAIL_CHECK("accepted an unknown extension");
        } catch (const InvalidInput& e) {
            CHECK(contains(e.what(), "extension"));
            CHECK(contains(e.what(), name));
        }
        CHECK(!fs::exists(dir / name));
    }
}

TEST_CASE("writers are deterministic and carry no time stamp") {
    ScratchDir dir("io-determ");
    const Image im = random_image(9, 11, 3, 0.0, 1.0, 7);
    write_tiff(dir / "a.tif", im, SampleFormat::kUint16);
    write_tiff(dir / "b.tif", im, SampleFormat::kUint16);
    CHECK(read_bytes(dir / "a.tif") == read_bytes(dir / "b.tif"));
    write_png(dir / "a.png", im, 8);
    write_png(dir / "b.png", im, 8);
    const std::string png = read_bytes(dir / "a.png");
    CHECK(png == read_bytes(dir / "b.png"));
    CHECK(!contains(png, "tIME"));
    CHECK(!contains(png, "tEXt"));
    TIFF* t = TIFFOpen((dir / "a.tif").c_str(), "r");
    REQUIRE(t != nullptr);
    char* text = nullptr;
    CHECK(TIFFGetField(t, TIFFTAG_DATETIME, &text) == 0);
    CHECK(TIFFGetField(t, TIFFTAG_SOFTWARE, &text) == 0);
    TIFFClose(t);
    // No temporary siblings are left behind by the atomic writes.
    int n_files = 0;
    for (const auto& e : fs::directory_iterator(dir.path())) n_files += e.is_regular_file();
    CHECK(n_files == 4);
}

TEST_CASE("npy files are written as numpy writes them: v1.0, padded to 64, C order") {
    ScratchDir dir("io-npyhdr");
    Image im(7, 5, 3);
    for (int k = 0; k < 3; ++k)
        for (int r = 0; r < 7; ++r)
            for (int c = 0; c < 5; ++c) im.channels[k](r, c) = r * 100 + c * 10 + k + 0.25;
    write_npy(dir / "a.npy", im, SampleFormat::kFloat32);
    const std::string b = read_bytes(dir / "a.npy");
    REQUIRE(b.size() > 10);
    CHECK(b.substr(0, 8) == std::string("\x93NUMPY\x01\x00", 8));
    const std::size_t hlen =
        std::size_t((unsigned char)b[8]) | (std::size_t((unsigned char)b[9]) << 8);
    CHECK((10 + hlen) % 64 == 0);
    const std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (7, 5, 3), }";
    CHECK(b.substr(10, dict.size()) == dict);
    CHECK(b[10 + hlen - 1] == '\n');
    REQUIRE(b.size() == 10 + hlen + 7 * 5 * 3 * 4);
    // The element at (r, c, k) = (2, 3, 1) sits at C-order index (2*5 + 3)*3 + 1, little-endian.
    const std::size_t off = 10 + hlen + ((2 * 5 + 3) * 3 + 1) * 4;
    std::uint32_t bits = 0;
    for (int i = 3; i >= 0; --i) bits = (bits << 8) | (unsigned char)b[off + i];
    CHECK(std::bit_cast<float>(bits) == 231.25f);

    if (std::system("/usr/bin/python3 -c 'import numpy' >/dev/null 2>&1") != 0) {
        MESSAGE("numpy cross-check skipped: /usr/bin/python3 with numpy is not available");
        return;
    }
    const std::string script =
        "import sys, numpy as np\n"
        "a = np.load(sys.argv[1])\n"
        "r, c, k = np.indices((7, 5, 3))\n"
        "ref = (r * 100 + c * 10 + k + 0.25).astype('<f4')\n"
        "np.save(sys.argv[2], ref.astype('<f8'))\n"
        "sys.exit(0 if a.dtype == np.float32 and a.shape == (7, 5, 3) and (a == ref).all() "
        "else 3)\n";
    write_bytes(dir / "check.py", script);
    const std::string cmd = "/usr/bin/python3 '" + (dir / "check.py").string() + "' '" +
                            (dir / "a.npy").string() + "' '" + (dir / "ref.npy").string() + "'";
    CHECK(std::system(cmd.c_str()) == 0);
    const LoadedImage ref = read_image(dir / "ref.npy");
    CHECK(ref.format == SampleFormat::kFloat64);
    REQUIRE(ref.image.n_channels() == 3);
    for (int k = 0; k < 3; ++k) CHECK((ref.image.channels[k] == im.channels[k]).all());
}

TEST_CASE("real sample files read with the figures their README gives") {
    const fs::path root = fs::path(PINMASK_SHARED_DIR) / "data" / "real";
    const fs::path psf = root / "waller-lab-diffusercam-tutorial" / "psf_sample.tif";
    const fs::path raw = root / "waller-lab-diffusercam-3d" / "example_raw.png";
    const fs::path stack = root / "waller-lab-diffusercam-3d" / "psf_stack" / "psf00.tiff";
    if (!fs::exists(psf) || !fs::exists(raw) || !fs::exists(stack)) {
        MESSAGE("real-file checks skipped: sample data not found under " << root);
        return;
    }
    // The README rounds means/sums to the printed integer: half a unit.
    constexpr double kReadmeRounding = 0.5;
    {
        const LoadedImage im = read_image(psf);
        REQUIRE(im.image.n_channels() == 1);
        const Plane& p = im.image.channels[0];
        CHECK(p.rows() == 1200);
        CHECK(p.cols() == 1600);
        CHECK(im.format == SampleFormat::kUint16);
        CHECK(im.full_scale == 65535.0);
        CHECK(p.minCoeff() == 0.0);
        CHECK(p.maxCoeff() == 65520.0);
        CHECK((p == 65520.0).count() == 192);
        CHECK(std::fabs(p.mean() - 2294.0) <= kReadmeRounding);
    }
    {
        const LoadedImage im = read_image(raw);
        REQUIRE(im.image.n_channels() == 1);
        const Plane& p = im.image.channels[0];
        CHECK(p.rows() == 270);
        CHECK(p.cols() == 320);
        CHECK(im.format == SampleFormat::kUint16);
        CHECK(p.minCoeff() == 99.0);
        CHECK(p.maxCoeff() == 65535.0);
        CHECK((p == 65535.0).count() == 1);
        CHECK(std::fabs(p.topLeftCorner(15, 15).mean() - 115.0) <= kReadmeRounding);
    }
    {
        const LoadedImage im = read_image(stack);
        REQUIRE(im.image.n_channels() == 1);
        const Plane& p = im.image.channels[0];
        CHECK(p.rows() == 270);
        CHECK(p.cols() == 320);
        CHECK(im.format == SampleFormat::kFloat32);
        CHECK(im.full_scale == 1.0);
        CHECK(p.minCoeff() >= 0.0);
        CHECK(p.maxCoeff() <= 1.0);
        CHECK(std::fabs(p.sum() - 1662.0) <= kReadmeRounding);
    }
}
