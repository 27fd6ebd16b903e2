// Fabrication files read by independent tools, when installed (a missing tool skips its case
// with a MESSAGE): ezdxf reads a --units mm DXF ($INSUNITS 4, 0.440-unit pinholes, CIRCLE
// entities for round ones), KLayout reads OASIS and hierarchical GDSII as the same polygons as
// the flat GDSII (XOR area zero), gerbv renders circular flashes at their diameter (+-1 pixel).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/image/image_io.hpp"
#include "export/formats/dxf_writer.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/oasis_writer.hpp"
#include "export/layout/geometry.hpp"
#include "tests/export/export_fixtures.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/external_tool.hpp"

using namespace pinmask;
using pinmask::test::have_tool;
using pinmask::test::run_tool;
using pinmask::test::slurp;
using pinmask::test::TempDir;
using pinmask::test::write_bytes;

namespace {

// The paper's pitch (440 um) on an 8 x 8 pattern tiled 2 x 3, four pinholes.
Mask tiled_mask() {
    Mask m = pinmask::test::golden_mask();
    m.pattern.n = 8;
    m.pattern.pinholes = {{0, 0}, {2, 3}, {5, 6}, {7, 1}};
    m.pattern.tiles_rows = 2;
    m.pattern.tiles_cols = 3;
    return m;
}

}  // namespace

TEST_CASE("ezdxf reads a --units mm DXF: $INSUNITS 4, pinholes 0.440 units, CIRCLE entities") {
    if (!have_tool("/usr/bin/python3 -c 'import ezdxf'")) {
        MESSAGE("skipped: python3-ezdxf is not installed");
        return;
    }
    TempDir dir("ext-dxf-mm");
    const Layout sq = make_layout(tiled_mask(), {});
    write_bytes(dir / "sq.dxf", dxf_document(sq, {.unit = FabUnit::kMillimetre}));
    LayoutOptions round;
    round.shape = HoleShape::kCircle;
    round.hole_side_m = 300e-6;
    const Layout rd = make_layout(tiled_mask(), round);
    write_bytes(dir / "rd.dxf",
                dxf_document(rd, {.unit = FabUnit::kMillimetre, .native_circles = true}));
    write_bytes(
        dir / "probe.py",
        "import sys, ezdxf\n"
        "for path in sys.argv[1:]:\n"
        "    doc = ezdxf.readfile(path)\n"
        "    msp = doc.modelspace()\n"
        "    sides = set()\n"
        "    for e in msp.query('POLYLINE'):\n"
        "        xs = [v.dxf.location.x for v in e.vertices]\n"
        "        sides.add(round(max(xs) - min(xs), 9))\n"
        "    circles = msp.query('CIRCLE')\n"
        "    radii = set(round(c.dxf.radius, 9) for c in circles)\n"
        "    print(doc.header.get('$INSUNITS'), len(msp.query('POLYLINE')), len(circles), "
        "min(sides) if sides else 0, max(sides) if sides else 0, min(radii) if radii else 0)\n");
    const auto [rc, out] = run_tool(
        "/usr/bin/python3 " + (dir / "probe.py") + " " + (dir / "sq.dxf") + " " + (dir / "rd.dxf"),
        dir);
    REQUIRE(rc == 0);
    std::istringstream s(out);
    int units = 0, polylines = 0, circles = 0;
    double side_min = 0, side_max = 0, radius = 0;
    s >> units >> polylines >> circles >> side_min >> side_max >> radius;
    CHECK(units == 4);
    CHECK(std::size_t(polylines) == sq.polygons.size());
    CHECK(circles == 0);
    // Named tolerance: the probe rounds ezdxf's float differences to 9 decimals (1e-9 mm).
    constexpr double kProbeRounding = 1e-9;
    CHECK(std::fabs(side_min - 0.440) <= kProbeRounding);  // whole cells: 0.44 mm
    CHECK(std::fabs(side_max - 0.440) <= kProbeRounding);
    s >> units >> polylines >> circles >> side_min >> side_max >> radius;
    REQUIRE(s);
    CHECK(units == 4);
    CHECK(polylines == 0);
    CHECK(std::size_t(circles) == rd.circles.size());
    CHECK(std::fabs(radius - 0.150) <= kProbeRounding);
}

TEST_CASE("KLayout reads OASIS and hierarchical GDSII as the flat GDSII's polygons (XOR 0)") {
    if (!have_tool("command -v klayout")) {
        MESSAGE("skipped: klayout is not installed");
        return;
    }
    TempDir dir("ext-oas");
    for (Tone tone : {Tone::kClear, Tone::kDark}) {
        LayoutOptions o;
        o.tone = tone;
        o.marks = true;
        o.hole_side_m = 301.3e-6;
        const Layout l = make_layout(tiled_mask(), o);
        write_bytes(dir / "flat.gds", gds_stream(l));
        write_bytes(dir / "cells.gds", gds_stream(l, {.hierarchy = true}));
        write_bytes(dir / "m.oas", oasis_file(l));
        write_bytes(
            dir / "xor.py",
            "import pya\n"
            "keep = []\n"
            "def region(path):\n"
            "    ly = pya.Layout(); ly.read(path); keep.append(ly)\n"
            "    return pya.Region(ly.top_cell().begin_shapes_rec(ly.layer(1, 0))), ly.dbu\n"
            "a, da = region(A)\n"
            "for p in (B, C):\n"
            "    b, db = region(p)\n"
            "    print(a.count(), b.count(), round(da * 1e6), round(db * 1e6), (a ^ b).area(), "
            "a.area())\n");
        const auto [rc, out] =
            run_tool("QT_QPA_PLATFORM=offscreen klayout -b -rd A=" + (dir / "flat.gds") +
                         " -rd B=" + (dir / "m.oas") + " -rd C=" + (dir / "cells.gds") + " -r " +
                         (dir / "xor.py"),
                     dir);
        REQUIRE(rc == 0);
        std::istringstream s(out);
        for (int k = 0; k < 2; ++k) {
            long na = 0, nb = 0, dbu_a = 0, dbu_b = 0;
            double xor_area = -1, area = 0;
            s >> na >> nb >> dbu_a >> dbu_b >> xor_area >> area;
            REQUIRE(s);
            CHECK(std::size_t(na) == l.polygons.size() + l.annotations.size());
            CHECK(nb == na);
            CHECK(dbu_a == 1000);
            CHECK(dbu_b == 1000);
            CHECK(area > 0);
            CHECK(xor_area == 0);
        }
    }
}

TEST_CASE("gerbv renders circular flashes at their diameter (+-1 pixel)") {
    if (!have_tool("command -v gerbv")) {
        MESSAGE("skipped: gerbv is not installed");
        return;
    }
    TempDir dir("ext-flash");
    LayoutOptions o;
    o.shape = HoleShape::kCircle;
    o.hole_side_m = 301.3e-6;
    const Layout l = make_layout(tiled_mask(), o);
    write_bytes(dir / "m.gbr", gerber_document(l, true));
    constexpr double kDpi = 2540.0;  // 10 um pixels: a pinhole is 30.13 pixels across
    constexpr double kNmPerPixel = 25.4e6 / kDpi;
    // An anti-aliased edge thresholded at half grey lands within half a pixel of the true edge
    // on each side: the measured width is within one pixel of the diameter.
    constexpr double kEdgePx = 1.0;
    const auto [rc, out] = run_tool("gerbv -x png -D " + std::to_string(int(kDpi)) +
                                        " -B 0 -b '#FFFFFF' -f '#000000FF' -o " + (dir / "m.png") +
                                        " " + (dir / "m.gbr"),
                                    dir);
    REQUIRE(rc == 0);
    const LoadedImage img = read_image(dir / "m.png");
    const int rows = img.image.rows(), cols = img.image.cols();
    std::vector<char> dark(std::size_t(rows) * cols), seen(dark.size(), 0);
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x)
            dark[std::size_t(y) * cols + x] = img.image.channels[0](y, x) < 0.5 * img.full_scale;
    std::vector<std::pair<int, int>> sizes;
    for (int start = 0; start < rows * cols; ++start) {
        if (seen[start] || !dark[start]) continue;
        int r0 = rows, r1 = -1, c0 = cols, c1 = -1;
        std::vector<int> stack{start};
        seen[start] = 1;
        while (!stack.empty()) {
            const int p = stack.back();
            stack.pop_back();
            const int y = p / cols, x = p % cols;
            r0 = std::min(r0, y), r1 = std::max(r1, y), c0 = std::min(c0, x), c1 = std::max(c1, x);
            for (const int q : {p - cols, p + cols, x > 0 ? p - 1 : -1, x + 1 < cols ? p + 1 : -1})
                if (q >= 0 && q < rows * cols && !seen[q] && dark[q])
                    seen[q] = 1, stack.push_back(q);
        }
        sizes.push_back({c1 - c0 + 1, r1 - r0 + 1});
    }
    REQUIRE(sizes.size() == l.circles.size());
    const double d_px = double(l.circles[0].diameter_nm) / kNmPerPixel;
    for (const auto& [w, h] : sizes) {
        CHECK(std::abs(double(w) - d_px) <= kEdgePx);
        CHECK(std::abs(double(h) - d_px) <= kEdgePx);
    }
}
