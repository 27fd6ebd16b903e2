// JPEG captures on the command line: `pinmask decode` reads a JPEG capture by its content as it
// reads a PNG of the same 8-bit counts (within the quality-100 round-trip error), and a truncated
// JPEG exits 2 naming the file and the problem, writing nothing.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image/image_io.hpp"
#include "tests/cli/generated_masks.hpp"
#include "tests/core/jpeg_writer.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using pinmask::test::run_cli;
namespace fs = std::filesystem;

namespace {

// The same capture as an 8-bit PNG and as a quality-100 grey JPEG differs by at most 1-2 counts
// per pixel (tests/core/test_jpeg_io.cpp, kQ100GreyMaxAbsCounts), DCT rounding noise; the Wiener
// decode at --nsr 1e-3 amplifies it by at most 1 / (2 sqrt(NSR)) = 16 in the weakest frequency.
// Measured: mean |difference| of the two decodes 0.84 % of the PNG decode's mean |value|; a
// capture read wrongly (transposed, channel mix-up, shifted, scaled) differs by tens of percent.
constexpr double kJpegVsPngDecodeRelTol = 0.03;

void write_file(const std::string& path, const std::string& bytes) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    REQUIRE(f != nullptr);
    REQUIRE(std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size());
    std::fclose(f);
}

}  // namespace

TEST_CASE("decode reads a JPEG capture, and refuses a truncated one with exit 2") {
    test::GeneratedMasks m("cli-jpeg");
    const std::string png16 = m.dir / "cap16.png";
    REQUIRE(run_cli("simulate " + m.a + " --scene letter-R --snr inf -o " + png16).exit_code == 0);
    // The capture's 8-bit counts, written once as PNG and once as JPEG.
    const Image cap = read_image(png16).image;
    REQUIRE(cap.n_channels() == 1);
    const double peak = cap.channels[0].maxCoeff();
    REQUIRE(peak > 0);
    std::vector<unsigned char> counts(std::size_t(cap.rows()) * cap.cols());
    Image eight(cap.rows(), cap.cols(), 1);
    for (int r = 0; r < cap.rows(); ++r) {
        for (int c = 0; c < cap.cols(); ++c) {
            const long q = std::lround(cap.channels[0](r, c) / peak * 255.0);
            counts[std::size_t(r) * cap.cols() + c] = static_cast<unsigned char>(q);
            eight.channels[0](r, c) = double(q) / 255.0;
        }
    }
    const std::string png8 = m.dir / "cap8.png", jpg = m.dir / "cap.jpg";
    write_png(png8, eight, 8);
    test::JpegSpec grey;
    grey.input = JCS_GRAYSCALE;
    const std::string bytes = test::encode_jpeg(counts, cap.rows(), cap.cols(), grey);
    write_file(jpg, bytes);

    const std::string from_png = m.dir / "from-png.tiff", from_jpg = m.dir / "from-jpg.tiff";
    const std::string flags = " --mask " + m.a + " --nsr 1e-3 -o ";
    const auto rp = run_cli("decode " + png8 + flags + from_png);
    INFO(rp.err);
    REQUIRE(rp.exit_code == 0);
    const auto rj = run_cli("decode " + jpg + flags + from_jpg);
    INFO(rj.err);
    REQUIRE(rj.exit_code == 0);
    const Image a = read_image(from_png).image, b = read_image(from_jpg).image;
    REQUIRE(a.rows() == b.rows());
    REQUIRE(a.cols() == b.cols());
    const double rel = (a.channels[0] - b.channels[0]).abs().mean() / a.channels[0].abs().mean();
    MESSAGE("JPEG vs PNG capture: relative mean decode difference " << rel);
    CHECK(rel < kJpegVsPngDecodeRelTol);

    const std::string cut = m.dir / "cut.jpg", out = m.dir / "cut-out.tiff";
    write_file(cut, bytes.substr(0, bytes.size() / 2));
    const auto rc = run_cli("decode " + cut + flags + out);
    CHECK(rc.exit_code == 2);
    CHECK(rc.err.find("cut.jpg") != std::string::npos);
    CHECK(rc.err.find("truncated") != std::string::npos);
    CHECK(!fs::exists(out));
}
