// core/image/raw_io: DNG files written here with libtiff (known CFA values) read back through
// LibRaw; the documented black-level subtraction and the Bayer binnings give the known values
// exactly.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "core/image/raw_io.hpp"
#include "tests/core/dng_writer.hpp"

using namespace pinmask;
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path dir = fs::temp_directory_path() / ("pinmask-raw-" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(dir); }
    ~TempDir() { fs::remove_all(dir); }
};

// Raw counts: black of the sample's 2 x 2 position + a known signal.
test::DngSpec known_dng(std::array<float, 4> black) {
    test::DngSpec s;
    s.black = black;
    s.values.resize(static_cast<std::size_t>(s.rows) * s.cols);
    for (int r = 0; r < s.rows; ++r)
        for (int c = 0; c < s.cols; ++c)
            s.values[static_cast<std::size_t>(r) * s.cols + c] = static_cast<std::uint16_t>(
                black[static_cast<std::size_t>((r % 2) * 2 + c % 2)] + 10 * r + c + 1);
    return s;
}

double signal(int r, int c) { return 10 * r + c + 1; }

}  // namespace

TEST_CASE("raw_io: a DNG decodes to the known values after black subtraction") {
    TempDir t;
    for (const auto black :
         {std::array<float, 4>{64, 64, 64, 64}, std::array<float, 4>{60, 70, 80, 90}}) {
        CAPTURE(black[1]);
        const auto spec = known_dng(black);
        const fs::path p = t.dir / "known.dng";
        test::write_dng(p, spec);
        RawInfo info;
        const LoadedImage sum = read_raw(p, BayerMode::kSum2x2, &info);
        REQUIRE(sum.image.rows() == spec.rows / 2);
        REQUIRE(sum.image.cols() == spec.cols / 2);
        CHECK(info.binning == 2);
        CHECK(info.white == 4095);
        CHECK(info.note.find("twice") != std::string::npos);
        const double min_black = *std::min_element(black.begin(), black.end());
        CHECK(sum.full_scale == doctest::Approx(4 * (4095 - min_black)).epsilon(0.03));
        // One read per mode (each read runs LibRaw in a child process).
        const Plane red = read_raw(p, BayerMode::kRed).image.channels[0];
        const Plane blue = read_raw(p, BayerMode::kBlue).image.channels[0];
        const Plane green = read_raw(p, BayerMode::kGreen).image.channels[0];
        for (int r = 0; r < spec.rows / 2; ++r)
            for (int c = 0; c < spec.cols / 2; ++c) {
                const double s00 = signal(2 * r, 2 * c), s01 = signal(2 * r, 2 * c + 1),
                             s10 = signal(2 * r + 1, 2 * c), s11 = signal(2 * r + 1, 2 * c + 1);
                CHECK(sum.image.channels[0](r, c) == s00 + s01 + s10 + s11);
                CHECK(red(r, c) == s00);
                CHECK(blue(r, c) == s11);
                CHECK(green(r, c) == 0.5 * (s01 + s10));
            }
        // The common entry point reads RAW by extension (default sum2x2).
        CHECK((read_image(p).image.channels[0] - sum.image.channels[0]).abs().maxCoeff() == 0);
    }
}

TEST_CASE("raw_io: a BGGR pattern is honoured") {
    TempDir t;
    auto spec = known_dng({64, 64, 64, 64});
    spec.cfa = {2, 1, 1, 0};
    test::write_dng(t.dir / "bggr.dng", spec);
    const LoadedImage r = read_raw(t.dir / "bggr.dng", BayerMode::kRed);
    CHECK(r.image.channels[0](1, 2) == signal(3, 5));  // red is the block's bottom-right
}

TEST_CASE("raw_io: malformed files are InvalidInput with LibRaw's reason") {
    TempDir t;
    const fs::path junk = t.dir / "junk.nef";
    std::ofstream(junk) << "this is not a raw file at all, just text that is long enough";
    try {
        read_image(junk);
        FAIL("no error");
    } catch (const InvalidInput& e) {
        const std::string m = e.what();
        CHECK(m.find("camera RAW file") != std::string::npos);
        CHECK(m.find("LibRaw: ") != std::string::npos);
    }
    CHECK_THROWS_AS(read_raw(t.dir / "absent.dng"), InvalidInput);
    CHECK_THROWS_AS(parse_bayer_mode("rggb"), InvalidInput);
    CHECK(parse_bayer_mode("g") == BayerMode::kGreen);
}

// Debian 12's LibRaw (0.20.2) aborts (glibc's buffer-overflow check in parseHassyModel) on a DNG
// whose make is Hasselblad and whose model fills its 64-byte field: the file is refused by name
// and this process goes on. A LibRaw without the bug may read it (then the values must be right).
TEST_CASE("raw_io: a file that crashes LibRaw is refused, and the caller survives") {
    TempDir t;
    auto spec = known_dng({64, 64, 64, 64});
    spec.make = "Hasselblad";
    spec.model = std::string(63, 'M');
    const fs::path p = t.dir / "hassy.dng";
    test::write_dng(p, spec);
    try {
        const LoadedImage im = read_raw(p, BayerMode::kRed);
        MESSAGE("this LibRaw reads the long Hasselblad model without crashing");
        CHECK(im.image.channels[0](1, 2) == signal(2, 4));
    } catch (const InvalidInput& e) {
        const std::string m = e.what();
        CHECK(m.find("camera RAW file '" + p.string() + "': LibRaw crashed reading this file") !=
              std::string::npos);
        CHECK(m.find("signal 6 (Aborted)") != std::string::npos);
    }
    // The same reader still works afterwards.
    test::write_dng(t.dir / "fine.dng", known_dng({64, 64, 64, 64}));
    CHECK(read_raw(t.dir / "fine.dng", BayerMode::kRed).image.channels[0](1, 2) == signal(2, 4));
}
