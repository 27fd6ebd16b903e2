#include <doctest/doctest.h>

#include <random>

#include "core/errors/error.hpp"
#include "export/formats/decimal.hpp"
#include "export/formats/dxf_writer.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/read_any.hpp"
#include "export/formats/svg_writer.hpp"
#include "export/formats/write_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;

namespace {

constexpr FabFormat kReadable[] = {FabFormat::kSvg, FabFormat::kGds, FabFormat::kDxf,
                                   FabFormat::kGerber};

std::vector<Layout> sample_layouts() {
    std::vector<Layout> out;
    out.push_back(make_layout(pinmask::test::golden_mask(), {}));
    LayoutOptions o;
    o.tone = Tone::kDark;
    o.frame_m = 150e-6;
    o.marks = true;
    o.label_lines = default_label_lines(pinmask::test::golden_mask(), "r");
    out.push_back(make_layout(pinmask::test::golden_mask(), o));
    o.shape = HoleShape::kCircle;
    o.chord_tolerance_m = 30e-9;
    o.mirror = true;
    o.max_vertices = 12;
    out.push_back(make_layout(pinmask::test::golden_mask(), o));
    LayoutOptions u;
    u.grid_m = 10e-9;
    out.push_back(make_layout(pinmask::test::random_dense_mask(13, 0.5, 3, 2), u));
    return out;
}

}  // namespace

TEST_CASE("every readable format reads back exactly the polygons written, and the metadata") {
    for (const Layout& l : sample_layouts())
        for (FabFormat f : kReadable) {
            INFO("format " << fab_format_name(f) << ", tone " << tone_name(l.tone));
            const FileGeometry g = read_fabrication_bytes(write_fabrication_bytes(l, f), f);
            CHECK(canonical_rings(g.rings) == canonical_rings(all_rings(l)));
            CHECK(g.rings.size() == l.polygons.size() + l.annotations.size());
            CHECK(g.info.at("hash") == l.mask_hash);
            CHECK(g.info.at("tone") == tone_name(l.tone));
            CHECK(g.info.at("mirrored") == (l.mirrored ? "yes" : "no"));
        }
}

TEST_CASE("truncated files are rejected with InvalidInput at every length") {
    const Layout l = sample_layouts()[1];
    for (FabFormat f : kReadable) {
        const std::string full = write_fabrication_bytes(l, f);
        // Text files may lose trailing whitespace and stay complete.
        const std::size_t complete =
            f == FabFormat::kGds ? full.size() : full.find_last_not_of(" \r\n") + 1;
        const std::size_t step = std::max<std::size_t>(1, complete / 3000);
        INFO("format " << fab_format_name(f));
        for (std::size_t n = 0; n < complete; n += step)
            CHECK_THROWS_AS(read_fabrication_bytes(std::string_view(full).substr(0, n), f),
                            InvalidInput);
        CHECK_NOTHROW(read_fabrication_bytes(std::string_view(full).substr(0, complete), f));
    }
}

TEST_CASE("garbage and mutated files give InvalidInput or a result, never another failure") {
    std::mt19937_64 rng(11);
    const Layout l = sample_layouts()[0];
    for (FabFormat f : kReadable) {
        const std::string good = write_fabrication_bytes(l, f);
        for (int trial = 0; trial < 400; ++trial) {
            std::string bytes;
            if (trial % 2 == 0) {  // random bytes, sometimes with a valid start
                bytes.resize(rng() % 300);
                for (char& c : bytes) c = static_cast<char>(rng());
                if (trial % 4 == 0) bytes = good.substr(0, 40) + bytes;
            } else {  // a few random byte changes in a valid file
                bytes = good;
                for (int k = 0; k < 1 + int(rng() % 4); ++k)
                    bytes[rng() % bytes.size()] = static_cast<char>(rng());
            }
            try {
                (void)read_fabrication_bytes(bytes, f);
            } catch (const InvalidInput&) {
            }  // any other exception type fails the test case
        }
    }
}

TEST_CASE("specific malformed inputs name the problem") {
    auto fails = [](std::string_view bytes, FabFormat f, std::string_view what) {
        try {
            (void)read_fabrication_bytes(bytes, f);
        } catch (const InvalidInput& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find(what) != std::string::npos);
            return;
        }
        FAIL("accepted: " << bytes.substr(0, 60));
    };
    const std::string svg_head =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 1 1\">\n<path d=\"";
    fails(svg_head + "M0,0l1,0L1,1Z\"/>\n</svg>\n", FabFormat::kSvg, "not supported");
    fails(svg_head + "M0,0L1.0005,0L1,1Z\"/>\n</svg>\n", FabFormat::kSvg, "grid");
    fails(svg_head + "M0,0L1,0L1,1\"/>\n</svg>\n", FabFormat::kSvg, "not closed");
    fails(svg_head + "M0,0L1,0L1,1Z\"/>\n", FabFormat::kSvg, "</svg>");
    const std::string gbr = "%FSLAX46Y46*%\n%MOMM*%\nG36*\nX0Y0D02*\nX1Y0D01*\nX1Y1D01*\n";
    fails(gbr + "G37*\nM02*\n", FabFormat::kGerber, "not closed");
    fails("%FSLAX46Y46*%\n%MOIN*%\nM02*\n", FabFormat::kGerber, "millimetres");
    fails("%FSLAX46Y46*%\n%MOMM*%\nX0Y0D03*\nM02*\n", FabFormat::kGerber,
          "without a selected aperture");
    fails("%FSLAX46Y46*%\n%MOMM*%\n%ADD10R,0.1X0.1*%\nM02*\n", FabFormat::kGerber,
          "unsupported aperture");
    fails("%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,0.1X0.05*%\nM02*\n", FabFormat::kGerber, "hole");
    fails(gbr + "X0Y0D01*\nG37*\n", FabFormat::kGerber, "M02");
    const std::string dxf = "0\nSECTION\n2\nENTITIES\n0\nPOLYLINE\n8\nL\n66\n1\n70\n";
    const std::string verts =
        "0\nVERTEX\n10\n0\n20\n0\n0\nVERTEX\n10\n1\n20\n0\n0\nVERTEX\n"
        "10\n1\n20\n1\n";
    fails(dxf + "0\n" + verts + "0\nSEQEND\n0\nENDSEC\n0\nEOF\n", FabFormat::kDxf, "not closed");
    fails(dxf + "1\n" + verts + "42\n0.5\n0\nSEQEND\n0\nENDSEC\n0\nEOF\n", FabFormat::kDxf,
          "bulge");
    fails("0\nSECTION\n2\nENTITIES\n0\nARC\n10\n0\n0\nENDSEC\n0\nEOF\n", FabFormat::kDxf,
          "unsupported entity");
    fails("0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\n0\n0\nENDSEC\n0\nEOF\n", FabFormat::kDxf,
          "CIRCLE without 10/20/40");
    fails(dxf + "1\n" + verts + "0\nSEQEND\n0\nENDSEC\n", FabFormat::kDxf, "EOF");
    std::string gds = gds_stream(sample_layouts()[0]);
    fails(std::string("\x00\x02\x00\x02", 4) + gds.substr(4), FabFormat::kGds, "length");
    fails(gds + "x", FabFormat::kGds, "after ENDLIB");
    CHECK_NOTHROW(read_fabrication_bytes(gds + std::string(100, '\0'), FabFormat::kGds));
    CHECK_THROWS_AS(read_fabrication_bytes("x", FabFormat::kPdf), InvalidInput);
}

TEST_CASE("DXF LWPOLYLINE entities are read too") {
    const std::string dxf =
        "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\nL\n90\n3\n70\n1\n10\n0\n20\n0\n10\n2.5\n20\n"
        "0\n10\n2.5\n20\n-1.25\n0\nENDSEC\n0\nEOF\n";
    const FileGeometry g = read_fabrication_bytes(dxf, FabFormat::kDxf);
    REQUIRE(g.rings.size() == 1);
    CHECK(g.rings[0] == Ring{{0, 0}, {2500, 0}, {2500, -1250}});
}

TEST_CASE("exact decimals: nanometres written as um or mm read back unchanged") {
    std::mt19937_64 rng(3);
    for (int i = 0; i < 20000; ++i) {
        const std::int64_t v = std::int64_t(rng() % 4'000'000'000'000ULL) - 2'000'000'000'000LL;
        for (int digits : {0, 3, 6}) {
            std::string s;
            append_scaled(s, v, digits);
            CHECK(parse_scaled(s, digits, "v") == v);
        }
    }
    std::string s;
    append_scaled(s, -1500, 3);
    CHECK(s == "-1.5");
    CHECK(parse_scaled("12.3450000", 3, "v") == 12345);
    CHECK(parse_scaled("0.0019999", 3, "v") == 2);  // within 0.001 unit: rounded
    CHECK(parse_scaled("0.0010001", 3, "v") == 1);
    CHECK(parse_scaled(".5", 3, "v") == 500);
    CHECK_THROWS_AS(parse_scaled("0.0015", 3, "v"), InvalidInput);
    CHECK_THROWS_AS(parse_scaled("1e3", 3, "v"), InvalidInput);
    CHECK_THROWS_AS(parse_scaled("", 3, "v"), InvalidInput);
    CHECK_THROWS_AS(parse_scaled("-", 3, "v"), InvalidInput);
    CHECK_THROWS_AS(parse_scaled("99999999999999999999", 3, "v"), InvalidInput);
}
