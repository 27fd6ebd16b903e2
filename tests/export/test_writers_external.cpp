// Cross-checks of the written files with independent readers, when installed (optional tools of
// scripts/install-deps; each check is skipped, and says so, when its tool is absent):
// KLayout (GDSII, DXF), ezdxf (DXF), gerbv (Gerber), librsvg (SVG).
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/image/image_io.hpp"
#include "export/formats/dxf_writer.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/svg_writer.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "tests/export/export_fixtures.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;

namespace {

bool have(const char* tool) {
    return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

// Runs a shell command and returns its stdout (exit status in *status).
std::string run(const std::string& cmd, int* status) {
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return out;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    *status = pclose(p);
    return out;
}

Layout busy() {
    LayoutOptions o;
    o.shape = HoleShape::kCircle;
    o.chord_tolerance_m = 100e-9;
    o.tone = Tone::kDark;
    o.frame_m = 200e-6;
    o.marks = true;
    o.label_lines = default_label_lines(pinmask::test::golden_mask(), "x");
    o.max_vertices = 40;
    return make_layout(pinmask::test::golden_mask(), o);
}

// Exact area of all rings in um^2 (rings never overlap).
double area_um2(const Layout& l) {
    WideInt a = 0;
    for (const Ring& r : all_rings(l)) a += doubled_area(r);
    return double(a) / 2 * 1e-6;
}

// The reported areas are sums of doubles over a few hundred polygons.
constexpr double kAreaRelTol = 1e-9;

}  // namespace

TEST_CASE("KLayout reads the GDSII and DXF files: same polygon count and area") {
    if (!have("klayout")) {
        MESSAGE("skipped: klayout is not installed");
        return;
    }
    const Layout l = busy();
    pinmask::test::TempDir dir("klayout");
    std::ofstream(dir / "m.gds", std::ios::binary) << gds_stream(l);
    std::ofstream(dir / "m.dxf", std::ios::binary) << dxf_document(l);
    std::ofstream(dir / "read.py") << R"(import pya
for f in [gds, dxf]:
    ly = pya.Layout()
    ly.read(f)
    top = ly.top_cell()
    n = 0
    area = 0.0
    for li in ly.layer_indexes():
        reg = pya.Region(top.shapes(li))
        n += reg.count()
        area += reg.area() * ly.dbu * ly.dbu
    print(n, repr(area))
)";
    int status = -1;
    const std::string out = run("klayout -b -r '" + (dir / "read.py") + "' -rd gds='" +
                                    (dir / "m.gds") + "' -rd dxf='" + (dir / "m.dxf") + "' 2>&1",
                                &status);
    INFO(out);
    REQUIRE(status == 0);
    std::istringstream in(out);
    const double want = area_um2(l);
    for (int k = 0; k < 2; ++k) {
        std::size_t n = 0;
        double area = 0;
        in >> n >> area;
        CHECK(n == l.polygons.size() + l.annotations.size());
        CHECK(std::fabs(area - want) <= kAreaRelTol * want);
    }
}

TEST_CASE("ezdxf reads the DXF: R12, closed polylines, same vertices and area") {
    if (std::system("/usr/bin/python3 -c 'import ezdxf' >/dev/null 2>&1") != 0) {
        MESSAGE("skipped: python3-ezdxf is not installed");
        return;
    }
    const Layout l = busy();
    pinmask::test::TempDir dir("ezdxf");
    std::ofstream(dir / "m.dxf", std::ios::binary) << dxf_document(l, {.layer = "HOLES"});
    std::ofstream(dir / "read.py") << R"(import sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
closed = 0
verts = 0
area = 0.0
for e in doc.modelspace():
    assert e.dxftype() == "POLYLINE" and e.dxf.layer == "HOLES"
    closed += 1 if e.is_closed else 0
    pts = [v.dxf.location for v in e.vertices]
    verts += len(pts)
    area += 0.5 * sum(pts[i].x * pts[(i + 1) % len(pts)].y - pts[(i + 1) % len(pts)].x * pts[i].y
                      for i in range(len(pts)))
print(doc.dxfversion, closed, verts, repr(area), len(doc.audit().errors))
)";
    int status = -1;
    const std::string out =
        run("/usr/bin/python3 '" + (dir / "read.py") + "' '" + (dir / "m.dxf") + "' 2>&1", &status);
    INFO(out);
    REQUIRE(status == 0);
    std::istringstream in(out);
    std::string version;
    std::size_t closed = 0, verts = 0, errors = 1;
    double area = 0;
    in >> version >> closed >> verts >> area >> errors;
    std::size_t want_verts = 0;
    for (const Ring& r : all_rings(l)) want_verts += r.size();
    CHECK(version == "AC1009");
    CHECK(closed == l.polygons.size() + l.annotations.size());
    CHECK(verts == want_verts);
    CHECK(std::fabs(area - area_um2(l)) <= kAreaRelTol * area_um2(l));
    CHECK(errors == 0);
}

TEST_CASE("gerbv renders the Gerber file at the extent's size") {
    if (!have("gerbv")) {
        MESSAGE("skipped: gerbv is not installed");
        return;
    }
    const Layout l = make_layout(pinmask::test::golden_mask(), {});
    pinmask::test::TempDir dir("gerbv");
    std::ofstream(dir / "m.gbr", std::ios::binary) << gerber_document(l);
    int status = -1;
    const std::string out =
        run("gerbv -x png -D 2540 -B 0 -o '" + (dir / "m.png") + "' '" + (dir / "m.gbr") + "' 2>&1",
            &status);
    INFO(out);
    REQUIRE(status == 0);
    const LoadedImage img = read_image(dir / "m.png");
    // The three pinholes span x -880..440 um and y -880..880 um: 132 x 176 px at 100 px/mm.
    // gerbv's autoscaled export adds up to one pixel per side around the drawing.
    constexpr int kGerbvBorderPixels = 2;
    CHECK(std::abs(img.image.cols() - 132) <= kGerbvBorderPixels);
    CHECK(std::abs(img.image.rows() - 176) <= kGerbvBorderPixels);
}

TEST_CASE("librsvg renders the SVG 1:1 with the pinholes where the layout has them") {
    if (!have("rsvg-convert")) {
        MESSAGE("skipped: rsvg-convert (librsvg2-bin) is not installed");
        return;
    }
    const Layout l = make_layout(pinmask::test::golden_mask(), {});
    pinmask::test::TempDir dir("rsvg");
    std::ofstream(dir / "m.svg", std::ios::binary) << svg_document(l);
    int status = -1;
    const std::string out = run("rsvg-convert -d 2540 -p 2540 -b white -o '" + (dir / "m.png") +
                                    "' '" + (dir / "m.svg") + "' 2>&1",
                                &status);
    INFO(out);
    REQUIRE(status == 0);
    const LoadedImage img = read_image(dir / "m.png");
    REQUIRE(img.image.cols() == 176);  // 1.76 mm at 100 px/mm
    REQUIRE(img.image.rows() == 176);
    const Plane& g = img.image.channels[0];
    const double half = 0.5 * img.full_scale;
    CHECK(g(22, 22) < half);    // pinhole (0, 0), top-left: filled
    CHECK(g(66, 110) < half);   // pinhole (1, 2)
    CHECK(g(154, 110) < half);  // pinhole (3, 2), bottom row
    CHECK(g(110, 22) > half);   // empty cell (2, 0)
}
