// Cross-checks of the fabrication writers with independent readers, when installed (Debian:
// python3-ezdxf, klayout, gerbv, librsvg2-bin, poppler-utils; scripts/install-deps
// --with-optional): each tool opens a file we wrote and must find our polygon count and
// bounding box. A missing tool skips its case with a MESSAGE naming it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/image/image_io.hpp"
#include "export/formats/dxf_writer.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/pdf_writer.hpp"
#include "export/formats/svg_writer.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/external_tool.hpp"

using namespace pinmask;
using pinmask::test::have_tool;
using pinmask::test::run_tool;
using pinmask::test::slurp;
using pinmask::test::TempDir;
using pinmask::test::write_bytes;

namespace {

// Raster renders are checked at 20 um per pixel (1270 dpi): the narrowest drawn feature (the
// 50 um mark bars) still covers two pixels and the image stays small.
constexpr double kDpi = 1270.0;
constexpr double kNmPerPixel = 25.4e6 / kDpi;
// An anti-aliased edge thresholded at half grey lands within one pixel of the true edge; the
// image size is the extent rounded up to whole pixels: 1.5 pixels covers both.
constexpr double kRasterEdgePx = 1.5;

// The layout every case writes: a 2 x 2 tiling of an 8 x 8 pattern (d = 440 um) with three
// pinholes, plus four alignment crosses; no label (its glyphs would merge in a raster).
Layout test_layout() {
    Mask m;
    m.pattern.n = 8;
    m.pattern.pinholes = {{0, 0}, {2, 3}, {5, 6}};
    LayoutOptions o;
    o.marks = true;
    return make_layout(m, o);
}

std::size_t ring_count(const Layout& l) { return l.polygons.size() + l.annotations.size(); }

// Connected components (4-neighbour) of pixels on one side of half grey.
struct Component {
    int r0, c0, r1, c1;  // inclusive pixel bounds
    long pixels = 0;
};
struct Raster {
    int rows = 0, cols = 0;
    std::vector<char> dark;
};

Raster load_raster(const std::string& path) {
    const LoadedImage img = read_image(path);
    Raster r{img.image.rows(), img.image.cols(), {}};
    r.dark.resize(std::size_t(r.rows) * r.cols);
    for (int y = 0; y < r.rows; ++y) {
        for (int x = 0; x < r.cols; ++x) {
            double v = 0;
            for (const auto& ch : img.image.channels) v += ch(y, x);
            r.dark[std::size_t(y) * r.cols + x] =
                v / double(img.image.channels.size()) < 0.5 * img.full_scale;
        }
    }
    return r;
}

std::vector<Component> components(const Raster& r, bool dark) {
    std::vector<char> seen(r.dark.size(), 0);
    std::vector<Component> out;
    std::vector<int> stack;
    for (int start = 0; start < r.rows * r.cols; ++start) {
        if (seen[start] || bool(r.dark[start]) != dark) continue;
        Component c{r.rows, r.cols, -1, -1, 0};
        stack.assign(1, start);
        seen[start] = 1;
        while (!stack.empty()) {
            const int p = stack.back();
            stack.pop_back();
            const int y = p / r.cols, x = p % r.cols;
            c.r0 = std::min(c.r0, y), c.r1 = std::max(c.r1, y);
            c.c0 = std::min(c.c0, x), c.c1 = std::max(c.c1, x);
            ++c.pixels;
            const int nb[4][2] = {{y - 1, x}, {y + 1, x}, {y, x - 1}, {y, x + 1}};
            for (const auto& n : nb) {
                if (n[0] < 0 || n[0] >= r.rows || n[1] < 0 || n[1] >= r.cols) continue;
                const int q = n[0] * r.cols + n[1];
                if (!seen[q] && bool(r.dark[q]) == dark) {
                    seen[q] = 1;
                    stack.push_back(q);
                }
            }
        }
        out.push_back(c);
    }
    return out;
}

// Dark components of a render of the drawn rings (black on white): one per ring, together
// spanning the extent.
void check_render_of_rings(const std::string& png, const Layout& l) {
    const Raster r = load_raster(png);
    const auto comps = components(r, true);
    CHECK(comps.size() == ring_count(l));
    Component all{r.rows, r.cols, -1, -1, 0};
    for (const auto& c : comps) {
        all = {std::min(all.r0, c.r0), std::min(all.c0, c.c0), std::max(all.r1, c.r1),
               std::max(all.c1, c.c1), 0};
    }
    const double w_px = double(l.extent.x1 - l.extent.x0) / kNmPerPixel;
    const double h_px = double(l.extent.y1 - l.extent.y0) / kNmPerPixel;
    CHECK(std::abs(double(r.cols) - w_px) <= kRasterEdgePx);
    CHECK(std::abs(double(r.rows) - h_px) <= kRasterEdgePx);
    CHECK(std::abs(double(all.c1 + 1 - all.c0) - w_px) <= kRasterEdgePx);
    CHECK(std::abs(double(all.r1 + 1 - all.r0) - h_px) <= kRasterEdgePx);
}

}  // namespace

TEST_CASE("ezdxf reads our DXF: one closed POLYLINE per ring, the extent as bounding box") {
    if (!have_tool("/usr/bin/python3 -c 'import ezdxf'")) {
        MESSAGE("skipped: python3-ezdxf is not installed (/usr/bin/python3 -c 'import ezdxf')");
        return;
    }
    TempDir dir("ext-dxf");
    const Layout l = test_layout();
    write_bytes(dir / "m.dxf", dxf_document(l));
    write_bytes(dir / "probe.py",
                "import sys, ezdxf\n"
                "from ezdxf import bbox\n"
                "doc = ezdxf.readfile(sys.argv[1])\n"
                "msp = doc.modelspace()\n"
                "polys = [e for e in msp if e.dxftype() == 'POLYLINE']\n"
                "closed = sum(1 for e in polys if e.is_closed)\n"
                "ext = bbox.extents(msp)\n"
                "print(len(msp), len(polys), closed, ext.extmin.x, ext.extmin.y, ext.extmax.x, "
                "ext.extmax.y)\n");
    const auto [rc, out] =
        run_tool("/usr/bin/python3 " + (dir / "probe.py") + " " + (dir / "m.dxf"), dir);
    REQUIRE(rc == 0);
    std::istringstream s(out);
    std::size_t entities = 0, polylines = 0, closed = 0;
    double x0, y0, x1, y1;
    s >> entities >> polylines >> closed >> x0 >> y0 >> x1 >> y1;
    REQUIRE(s);
    CHECK(entities == ring_count(l));
    CHECK(polylines == ring_count(l));
    CHECK(closed == ring_count(l));
    // DXF coordinates are micrometres with three decimals: exact nanometres.
    CHECK(std::llround(x0 * 1e3) == l.extent.x0);
    CHECK(std::llround(y0 * 1e3) == l.extent.y0);
    CHECK(std::llround(x1 * 1e3) == l.extent.x1);
    CHECK(std::llround(y1 * 1e3) == l.extent.y1);
}

TEST_CASE("KLayout reads our GDSII: dbu 1 nm, one polygon per ring, one text, the extent") {
    if (!have_tool("command -v klayout")) {
        MESSAGE("skipped: klayout is not installed");
        return;
    }
    TempDir dir("ext-gds");
    const Layout l = test_layout();
    write_bytes(dir / "m.gds", gds_stream(l));
    write_bytes(dir / "probe.py",
                "import pya\n"
                "ly = pya.Layout()\n"
                "ly.read(path)\n"
                "top = ly.top_cell()\n"
                "polys = texts = 0\n"
                "for li in ly.layer_indexes():\n"
                "    for sh in top.shapes(li).each():\n"
                "        if sh.is_text(): texts += 1\n"
                "        elif sh.is_polygon() or sh.is_box(): polys += 1\n"
                "b = top.bbox()\n"
                "print(round(ly.dbu * 1e6), len(ly.top_cells()), polys, texts, b.left, b.bottom, "
                "b.right, b.top)\n");
    const auto [rc, out] =
        run_tool("QT_QPA_PLATFORM=offscreen klayout -b -rd path=" + (dir / "m.gds") + " -r " +
                     (dir / "probe.py"),
                 dir);
    REQUIRE(rc == 0);
    std::istringstream s(out);
    long dbu_pm = 0, tops = 0, polys = 0, texts = 0, x0, y0, x1, y1;
    s >> dbu_pm >> tops >> polys >> texts >> x0 >> y0 >> x1 >> y1;
    REQUIRE(s);
    CHECK(dbu_pm == 1000);  // 0.001 um = 1 nm
    CHECK(tops == 1);
    CHECK(std::size_t(polys) == ring_count(l));
    CHECK(texts == 1);  // the info text sits at a point inside the extent
    CHECK(x0 == l.extent.x0);
    CHECK(y0 == l.extent.y0);
    CHECK(x1 == l.extent.x1);
    CHECK(y1 == l.extent.y1);
}

TEST_CASE("gerbv reads our Gerber: one region per ring, rendered over the extent") {
    if (!have_tool("command -v gerbv")) {
        MESSAGE("skipped: gerbv is not installed");
        return;
    }
    TempDir dir("ext-gbr");
    const Layout l = test_layout();
    write_bytes(dir / "m.gbr", gerber_document(l));
    // gerbv's own RS-274X export of what it parsed: count its regions.
    auto [rc, out] =
        run_tool("gerbv -x rs274x -o " + (dir / "again.gbr") + " " + (dir / "m.gbr"), dir);
    REQUIRE(rc == 0);
    const std::string again = slurp(dir / "again.gbr");
    std::size_t regions = 0;
    for (auto p = again.find("G36"); p != std::string::npos; p = again.find("G36", p + 1))
        ++regions;
    CHECK(regions == ring_count(l));
    std::tie(rc, out) = run_tool("gerbv -x png -D " + std::to_string(int(kDpi)) +
                                     " -B 0 -b '#FFFFFF' -f '#000000FF' -o " + (dir / "m.png") +
                                     " " + (dir / "m.gbr"),
                                 dir);
    REQUIRE(rc == 0);
    check_render_of_rings(dir / "m.png", l);
}

TEST_CASE("rsvg-convert renders our SVG 1:1: one dark shape per ring over the extent") {
    if (!have_tool("command -v rsvg-convert")) {
        MESSAGE("skipped: rsvg-convert (librsvg2-bin) is not installed");
        return;
    }
    TempDir dir("ext-svg");
    const Layout l = test_layout();
    write_bytes(dir / "m.svg", svg_document(l));
    const std::string dpi = std::to_string(int(kDpi));
    const auto [rc, out] =
        run_tool("rsvg-convert -d " + dpi + " -p " + dpi + " -b white -f png -o " +
                     (dir / "m.png") + " " + (dir / "m.svg"),
                 dir);
    REQUIRE(rc == 0);
    check_render_of_rings(dir / "m.png", l);
}

TEST_CASE("poppler reads our PDF: one page, the film 1:1 at the margin with every pinhole") {
    if (!have_tool("command -v pdfinfo") || !have_tool("command -v pdftoppm")) {
        MESSAGE("skipped: poppler-utils (pdfinfo, pdftoppm) is not installed");
        return;
    }
    TempDir dir("ext-pdf");
    const Layout l = test_layout();
    const PdfOptions options;
    write_bytes(dir / "m.pdf", pdf_document(l, options));
    auto [rc, info] = run_tool("pdfinfo " + (dir / "m.pdf"), dir);
    REQUIRE(rc == 0);
    std::smatch m;
    REQUIRE(std::regex_search(info, m, std::regex(R"(Pages:\s+(\d+))")));
    CHECK(m[1] == "1");
    REQUIRE(std::regex_search(info, m, std::regex(R"(Page size:\s+([\d.]+) x ([\d.]+) pts)")));
    const double nm_per_pt = 25.4e6 / 72.0;
    const double margin_nm = options.margin_m * 1e9;
    CHECK(std::stod(m[1]) * nm_per_pt >= double(l.extent.x1 - l.extent.x0) + 2 * margin_nm - 1e3);
    CHECK(std::stod(m[2]) * nm_per_pt >= double(l.extent.y1 - l.extent.y0) + 2 * margin_nm - 1e3);
    std::string out;
    std::tie(rc, out) =
        run_tool("pdftoppm -r " + std::to_string(int(kDpi)) + " -gray -png -singlefile " +
                     (dir / "m.pdf") + " " + (dir / "page"),
                 dir);
    REQUIRE(rc == 0);
    const Raster r = load_raster(dir / "page.png");
    // Clear tone: the extent is painted black (the film) with the rings cut out in white.
    const auto dark = components(r, true);
    REQUIRE_FALSE(dark.empty());
    const auto film = *std::max_element(
        dark.begin(), dark.end(), [](const auto& a, const auto& b) { return a.pixels < b.pixels; });
    const double margin_px = margin_nm / kNmPerPixel;
    CHECK(std::abs(film.c0 - margin_px) <= kRasterEdgePx);
    CHECK(std::abs(film.r0 - margin_px) <= kRasterEdgePx);
    CHECK(std::abs(double(film.c1 + 1 - film.c0) -
                   double(l.extent.x1 - l.extent.x0) / kNmPerPixel) <= kRasterEdgePx);
    CHECK(std::abs(double(film.r1 + 1 - film.r0) -
                   double(l.extent.y1 - l.extent.y0) / kNmPerPixel) <= kRasterEdgePx);
    // White islands inside the film: every ring that does not reach the extent's border (the
    // corner crosses do, and join the white margin).
    std::size_t inner = 0;
    for (const auto* set : {&l.polygons, &l.annotations}) {
        for (const Ring& ring : *set) {
            const BoxNm b = bounding_box({ring});
            inner += b.x0 > l.extent.x0 && b.y0 > l.extent.y0 && b.x1 < l.extent.x1 &&
                     b.y1 < l.extent.y1;
        }
    }
    std::size_t islands = 0;
    for (const auto& c : components(r, false)) {
        islands += c.c0 > film.c0 && c.r0 > film.r0 && c.c1 < film.c1 && c.r1 < film.r1;
    }
    CHECK(inner == 12);  // 3 pinholes x 4 tiles
    CHECK(islands == inner);
}
