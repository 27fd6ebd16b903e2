// PNG preview and PDF scale, checked on pixels: the PNG through core/image/image_io, the PDF
// through poppler's pdftoppm when it is installed (an optional cross-check reader; skipped, and
// said so, when absent).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "export/formats/pdf_writer.hpp"
#include "export/formats/png_preview.hpp"
#include "export/layout/geometry.hpp"
#include "tests/export/export_fixtures.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;

namespace {

// Longest horizontal run of dark pixels (value below half scale) in the first channel.
int longest_dark_run(const LoadedImage& img) {
    const Plane& p = img.image.channels[0];
    int best = 0;
    for (Eigen::Index r = 0; r < p.rows(); ++r) {
        int run = 0;
        for (Eigen::Index c = 0; c < p.cols(); ++c) {
            run = p(r, c) < 0.5 * img.full_scale ? run + 1 : 0;
            best = std::max(best, run);
        }
    }
    return best;
}

// Antialiased edges may darken one extra pixel at each end of a run.
constexpr int kEdgePixels = 2;

}  // namespace

TEST_CASE("PNG preview: size from the dpi, black opaque plate, white clear pinholes") {
    const Layout l = make_layout(pinmask::test::golden_mask(), {});
    const double dpi = 2540;  // 100 px per mm: the 1.76 mm mask is 176 px
    const PreviewSize size = preview_size(l, dpi);
    CHECK(size.cols == 176);
    CHECK(size.rows == 176);
    pinmask::test::TempDir dir("png");
    const std::string path = dir / "p.png";
    std::ofstream(path, std::ios::binary) << png_preview(l, dpi);
    const LoadedImage img = read_image(path);
    REQUIRE(img.image.rows() == 176);
    REQUIRE(img.image.cols() == 176);
    const Plane& g = img.image.channels[0];
    CHECK(g(22, 22) > 0.9 * img.full_scale);    // centre of pinhole (0, 0): clear
    CHECK(g(110, 22) < 0.1 * img.full_scale);   // cell (2, 0): opaque
    CHECK(g(154, 110) > 0.9 * img.full_scale);  // pinhole (3, 2), row 3 is the bottom row
    CHECK_THROWS_AS(preview_size(l, 0), InvalidInput);
    CHECK_THROWS_AS(preview_size(l, 1e7), InvalidInput);
}

TEST_CASE("PDF is 1:1: rendered at 2540 dpi the 1.76 mm plate is 176 px wide") {
    if (std::system("command -v pdftoppm >/dev/null 2>&1") != 0) {
        MESSAGE("skipped: pdftoppm (poppler-utils) is not installed");
        return;
    }
    const Layout l = make_layout(pinmask::test::golden_mask(), {});
    pinmask::test::TempDir dir("pdf");
    std::ofstream(dir / "m.pdf", std::ios::binary) << pdf_document(l);
    const std::string cmd =
        "pdftoppm -r 2540 -gray -png -singlefile '" + (dir / "m.pdf") + "' '" + (dir / "m") + "'";
    REQUIRE(std::system(cmd.c_str()) == 0);
    const LoadedImage img = read_image(dir / "m.png");
    // Cell row 2 has no pinhole: a full-width black run of the plate.
    CHECK(std::abs(longest_dark_run(img) - 176) <= kEdgePixels);
}
