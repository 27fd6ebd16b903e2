// Fabrication formats and options inside the library: units (DXF drawing units and $INSUNITS,
// GDSII user unit), native circles, OASIS and GDSII hierarchy read back equal to the flat
// design, the 1-bit plotter raster against a direct pixel count, vendor presets, tone aliases.
// Answers are known by construction (the layout's own integer rings).
#include <doctest/doctest.h>
#include <tiffio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "export/formats/dxf_reader.hpp"
#include "export/formats/dxf_writer.hpp"
#include "export/formats/gds_reader.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/gerber_reader.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/oasis_reader.hpp"
#include "export/formats/oasis_writer.hpp"
#include "export/formats/plotter_raster.hpp"
#include "export/formats/png_preview.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/repetition.hpp"
#include "export/layout/shapes.hpp"
#include "export/pipeline/export_pipeline.hpp"
#include "export/pipeline/read_back.hpp"
#include "export/pipeline/vendor_presets.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;
using pinmask::test::golden_mask;
using pinmask::test::mask_with;

namespace {

// A 2 x 3 tiling of an 8 x 8 pattern with four pinholes (d = 440 um), squares of 301.3 um
// (not a whole number of 1 um plotter pixels), marks and a label.
Layout tiled_layout(Tone tone = Tone::kClear, HoleShape shape = HoleShape::kSquare) {
    Mask m = golden_mask();
    m.pattern.n = 8;
    m.pattern.pinholes = {{0, 0}, {2, 3}, {5, 6}, {7, 1}};
    m.pattern.tiles_rows = 2;
    m.pattern.tiles_cols = 3;
    LayoutOptions o;
    o.tone = tone;
    o.shape = shape;
    o.hole_side_m = 301.3e-6;
    o.marks = true;
    o.label_lines = default_label_lines(m, "t");
    return make_layout(m, o);
}

bool same_geometry(const FileGeometry& g, const Layout& l) {
    const ReadBack r = compare_with_layout(g, l);
    INFO(r.describe());
    return r.identical() && r.hash_ok();
}

}  // namespace

TEST_CASE("DXF in mm and inches reads back to the same nanometres; $INSUNITS is honoured") {
    const Layout l = tiled_layout();
    for (FabUnit u : {FabUnit::kMicrometre, FabUnit::kMillimetre, FabUnit::kInch}) {
        const std::string dxf = dxf_document(l, {.unit = u});
        CHECK(dxf.find("$INSUNITS\n 70\n" + std::to_string(dxf_insunits(u)) + "\n") !=
              std::string::npos);
        CHECK(dxf.find("$MEASUREMENT\n 70\n" + std::string(u == FabUnit::kInch ? "0" : "1")) !=
              std::string::npos);
        CHECK(same_geometry(read_dxf(dxf), l));
    }
    // A foreign file: $INSUNITS 1 (inches), no pinmask comment; 0.01 in = 254000 nm.
    const std::string inch =
        "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n1\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"
        "0\nLWPOLYLINE\n70\n1\n10\n0\n20\n0\n10\n0.01\n20\n0\n10\n0.01\n20\n0.01\n0\nENDSEC\n"
        "0\nEOF\n";
    const FileGeometry g = read_dxf(inch);
    REQUIRE(g.rings.size() == 1);
    CHECK(g.rings[0][2] == PointNm{254000, 254000});
    // In mm a pinhole of 0.44 mm is 440000 nm exactly.
    const std::string mm =
        "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\n"
        "ENTITIES\n0\nCIRCLE\n10\n1\n20\n2\n40\n0.22\n0\nENDSEC\n0\nEOF\n";
    const FileGeometry c = read_dxf(mm);
    REQUIRE(c.circles.size() == 1);
    CHECK(c.circles[0] == CircleNm{{1000000, 2000000}, 440000});
}

TEST_CASE("native circles: DXF CIRCLE and Gerber flashes carry each round pinhole exactly") {
    const Layout l = tiled_layout(Tone::kClear, HoleShape::kCircle);
    REQUIRE(l.circles.size() == l.polygons.size());
    for (FabUnit u : {FabUnit::kMicrometre, FabUnit::kMillimetre, FabUnit::kInch}) {
        const FileGeometry g = read_dxf(dxf_document(l, {.unit = u, .native_circles = true}));
        CHECK(g.circles.size() == l.circles.size());
        CHECK(same_geometry(g, l));
    }
    const std::string gbr = gerber_document(l, true);
    CHECK(gbr.find("%ADD10C,0.3013*%") != std::string::npos);  // 301.3 um in mm
    const FileGeometry g = read_gerber(gbr);
    CHECK(g.circles.size() == l.circles.size());
    CHECK(same_geometry(g, l));
    // A moved circle is found: the comparison is not vacuous.
    FileGeometry moved = g;
    moved.circles[0].centre.x += 1;
    CHECK_FALSE(compare_with_layout(moved, l).identical());
    CHECK(compare_with_layout(moved, l).xor_area_nm2 > 0);
}

TEST_CASE("OASIS and hierarchical GDSII read back identical to the flat layout") {
    for (Tone tone : {Tone::kClear, Tone::kDark})
        for (HoleShape shape : {HoleShape::kSquare, HoleShape::kCircle}) {
            const Layout l = tiled_layout(tone, shape);
            const std::string oas = oasis_file(l);
            CHECK(oas.starts_with("%SEMI-OASIS\r\n"));
            CHECK(same_geometry(read_oasis(oas), l));
            CHECK(same_geometry(read_oasis(oasis_file(l, {.repetitions = false})), l));
            const FileGeometry h = read_gds(gds_stream(l, {.hierarchy = true}));
            CHECK(same_geometry(h, l));
            CHECK(h.info.at("hierarchy") == "yes");
        }
    // Clear squares repeat across the 2 x 3 tiles: one tile and the array.
    const Layout l = tiled_layout();
    const Repetition r = find_repetition(l.polygons, l.active_area, l.tiles_rows, l.tiles_cols);
    CHECK(r.cols == 3);
    CHECK(r.rows == 2);
    CHECK(r.placements.size() == 4);
    CHECK(r.shapes.size() == 1);
    CHECK(canonical_rings(expand(r)) == canonical_rings(l.polygons));
    // A layout whose tiles differ has no array, and still expands to itself.
    Layout odd = l;
    odd.polygons.pop_back();
    const Repetition none =
        find_repetition(odd.polygons, odd.active_area, odd.tiles_rows, odd.tiles_cols);
    CHECK(none.cols * none.rows == 1);
    CHECK(canonical_rings(expand(none)) == canonical_rings(odd.polygons));
    CHECK(same_geometry(read_gds(gds_stream(odd, {.hierarchy = true})), odd));  // flat fallback
}

TEST_CASE("GDSII user unit follows --units; the database unit stays 1 nm") {
    const Layout l = tiled_layout();
    for (FabUnit u : {FabUnit::kMicrometre, FabUnit::kMillimetre, FabUnit::kInch}) {
        const std::string g = gds_stream(l, {.unit = u});
        // UNITS record: 4 bytes header after BGNLIB(28) LIBNAME(12) HEADER(6) = offset 46.
        const std::size_t at = g.find(std::string("\x00\x14\x03\x05", 4));
        REQUIRE(at != std::string::npos);
        std::uint64_t user = 0;
        for (int i = 0; i < 8; ++i) user = user << 8 | std::uint8_t(g[at + 4 + i]);
        // Named tolerance: the 56-bit GDSII mantissa, about 1e-16 relative.
        CHECK(gds_real8_value(user) ==
              doctest::Approx(1.0 / double(nm_per_unit(u))).epsilon(1e-15));
        CHECK(same_geometry(read_gds(g), l));
    }
}

TEST_CASE("1-bit plotter raster: size, pinholes and snapping error against a direct count") {
    const Layout l = tiled_layout();
    constexpr double kDpi = 25400;  // 1 um pixels
    const SnapReport s = plotter_snap_report(l, kDpi);
    CHECK(s.pixel_nm == doctest::Approx(1000.0));
    const PlotterRaster r = plotter_raster(l, kDpi);
    CHECK(r.cols == (l.extent.x1 - l.extent.x0 + 999) / 1000);
    CHECK(r.rows == (l.extent.y1 - l.extent.y0 + 999) / 1000);
    // Direct computation: for every pinhole, count its clear pixels along its centre row and
    // column; the size error is the count in nm minus the drawn side, the centre error the
    // mid-point of the run minus the drawn centre.
    double size_err = 0, pos_err = 0;
    for (const Ring& p : l.polygons) {
        const BoxNm b = bounding_box({p});
        const double cx = 0.5 * double(b.x0 + b.x1), cy = 0.5 * double(b.y0 + b.y1);
        const auto col = std::int64_t((cx - double(l.extent.x0)) / 1000);
        const auto row = std::int64_t((double(l.extent.y1) - cy) / 1000);
        REQUIRE_FALSE(r.opaque(row, col));
        std::int64_t c0 = col, c1 = col, r0 = row, r1 = row;
        while (!r.opaque(row, c0 - 1)) --c0;
        while (!r.opaque(row, c1 + 1)) ++c1;
        while (!r.opaque(r0 - 1, col)) --r0;
        while (!r.opaque(r1 + 1, col)) ++r1;
        const double w = double(c1 - c0 + 1) * 1000, h = double(r1 - r0 + 1) * 1000;
        size_err = std::max(
            {size_err, std::fabs(w - double(b.x1 - b.x0)), std::fabs(h - double(b.y1 - b.y0))});
        const double mx = double(l.extent.x0) + 0.5 * double(c0 + c1 + 1) * 1000;
        const double my = double(l.extent.y1) - 0.5 * double(r0 + r1 + 1) * 1000;
        pos_err = std::max({pos_err, std::fabs(mx - cx), std::fabs(my - cy)});
    }
    // Named tolerance: both are sums of a few doubles of whole and half nanometres.
    constexpr double kArithmeticNm = 1e-6;
    CHECK(std::fabs(s.max_size_error_nm - size_err) <= kArithmeticNm);
    CHECK(std::fabs(s.max_position_error_nm - pos_err) <= kArithmeticNm);
    CHECK(size_err > 0);  // 301.3 um is not a whole number of pixels: the test is not vacuous
    CHECK(size_err <= 1000);
    // Deterministic bytes (OASIS, hierarchical GDSII, TIFF: no dates, no addresses).
    CHECK(oasis_file(l) == oasis_file(tiled_layout()));
    CHECK(gds_stream(l, {.hierarchy = true}) == gds_stream(tiled_layout(), {.hierarchy = true}));
    CHECK(plotter_tiff(l, 2540, 0) == plotter_tiff(tiled_layout(), 2540, 0));
    // The TIFF refuses a coarse plotter.
    CHECK_THROWS_AS(plotter_tiff(l, 300, 5000), InvalidInput);
    CHECK(plotter_tiff(l, 2540, 0).starts_with("II*"));
}

TEST_CASE("vendor presets, tone aliases and nonsense options") {
    CHECK(find_vendor_preset("film") == nullptr);
    const VendorPreset* film = find_vendor_preset("film-plotter");
    REQUIRE(film);
    CHECK(film->unit == FabUnit::kMillimetre);
    CHECK(film->emulsion_down);
    CHECK(film->tiff_dpi == 25400);
    CHECK(std::find(film->formats.begin(), film->formats.end(), FabFormat::kTiff1) !=
          film->formats.end());
    const VendorPreset* chrome = find_vendor_preset("chrome-photomask");
    REQUIRE(chrome);
    CHECK(chrome->plate_m == doctest::Approx(0.107));
    CHECK(find_vendor_preset("laser-cutter")->kerf_m > 0);
    CHECK(find_vendor_preset("gerber-film")->native_circles);
    CHECK_THROWS_AS(find_vendor_preset("acme"), InvalidInput);
    CHECK(vendor_list_text().find("film-plotter") != std::string::npos);
    CHECK(parse_tone("negative", "--tone") == Tone::kClear);
    CHECK(parse_tone("positive", "--tone") == Tone::kDark);
    ExportOptions o;
    o.layout.hole_side_m = -1e-6;
    CHECK_THROWS_AS(o.validate(), InvalidInput);
    o = {};
    o.kerf_m = std::nan("");
    CHECK_THROWS_AS(o.validate(), InvalidInput);
    // Kerf: holes drawn smaller by the kerf.
    ExportOptions k;
    k.formats = {FabFormat::kDxf};
    k.kerf_m = 40e-6;
    const ExportSummary s = export_mask(golden_mask(), k);
    const BoxNm b = bounding_box({s.layout.polygons[0]});
    CHECK(b.x1 - b.x0 == 400000);
}

TEST_CASE("the kerf note states the hole as drawn on the grid, not the side asked for") {
    // A 301.407 um pinhole on the laser cutter's 1 um grid with its 20 um kerf: the side asked
    // for is 281.407 um; the file draws the polygon's edges on the grid.
    Mask m = golden_mask();
    m.camera.pinhole_m = 301.407e-6;
    ExportOptions k;
    k.formats = {FabFormat::kDxf};
    k.kerf_m = 20e-6;
    k.layout.grid_m = 1e-6;
    const ExportSummary s = export_mask(m, k);
    const BoxNm b = bounding_box({s.layout.polygons[0]});
    const std::int64_t drawn = b.x1 - b.x0;
    CHECK(drawn % 1000 == 0);
    std::string kerf_note;
    for (const std::string& n : s.notes)
        if (n.rfind("kerf ", 0) == 0) kerf_note = n;
    INFO(kerf_note);
    const std::string drawn_text = "holes drawn " + nm_text(double(drawn));
    CHECK(kerf_note.find(drawn_text + " (281407 nm before the 1000 nm grid)") != std::string::npos);
    CHECK(kerf_note.find("cut comes out at " + nm_text(double(drawn) + 20000.0)) !=
          std::string::npos);
    // On the grid already: no "before the grid" clause.
    m.camera.pinhole_m = 300e-6;
    const ExportSummary on = export_mask(m, k);
    for (const std::string& n : on.notes)
        if (n.rfind("kerf ", 0) == 0) CHECK(n.find("before the") == std::string::npos);
}

TEST_CASE("1-bit TIFF at 25400 dpi: physical size from its tags and the pinhole count") {
    const Layout l = tiled_layout();
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("pinmask-tiff1-" + std::to_string(::getpid()) + ".tif"))
                                 .string();
    std::ofstream(path, std::ios::binary) << plotter_tiff(l, 25400, 0);
    TIFF* t = TIFFOpen(path.c_str(), "r");
    REQUIRE(t);
    std::uint32_t w = 0, h = 0;
    std::uint16_t bits = 0, unit = 0, photometric = 0;
    float xres = 0, yres = 0;
    TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(t, TIFFTAG_IMAGELENGTH, &h);
    TIFFGetField(t, TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photometric);
    TIFFGetField(t, TIFFTAG_XRESOLUTION, &xres);
    TIFFGetField(t, TIFFTAG_YRESOLUTION, &yres);
    TIFFGetField(t, TIFFTAG_RESOLUTIONUNIT, &unit);
    CHECK(bits == 1);
    CHECK(photometric == PHOTOMETRIC_MINISWHITE);
    CHECK(unit == RESUNIT_INCH);
    CHECK(xres == 25400.0f);
    CHECK(yres == 25400.0f);
    // Physical size = pixels / dpi: the extent rounded up to whole 1 um pixels.
    const double width_m = double(w) / xres * 0.0254, height_m = double(h) / yres * 0.0254;
    constexpr double kOnePixelM = 1e-6;
    CHECK(std::fabs(width_m - double(l.extent.x1 - l.extent.x0) * 1e-9) < kOnePixelM);
    CHECK(std::fabs(height_m - double(l.extent.y1 - l.extent.y0) * 1e-9) < kOnePixelM);
    // Pinholes: runs of clear pixels on the rows through the pinhole centres of the active
    // area, counted as clear-run starts per row (every pinhole is a solid clear square).
    std::vector<std::uint8_t> row(TIFFScanlineSize(t));
    std::size_t starts = 0;
    std::set<std::int64_t> centre_rows;
    for (const Ring& p : l.polygons) {
        const BoxNm b = bounding_box({p});
        centre_rows.insert((l.extent.y1 - (b.y0 + b.y1) / 2) / 1000);
    }
    for (std::int64_t r = 0; r < std::int64_t(h); ++r) {  // compressed strips: rows in order
        REQUIRE(TIFFReadScanline(t, row.data(), std::uint32_t(r), 0) == 1);
        if (!centre_rows.count(r)) continue;
        bool prev_clear = false;
        for (std::uint32_t c = 0; c < w; ++c) {
            const bool clear = !(row[c / 8] & (0x80 >> (c % 8)));
            const double x = double(l.extent.x0) + (double(c) + 0.5) * 1000;
            const bool in_active = x > double(l.active_area.x0) && x < double(l.active_area.x1);
            if (clear && !prev_clear && in_active) ++starts;
            prev_clear = clear;
        }
    }
    TIFFClose(t);
    std::filesystem::remove(path);
    CHECK(starts == l.polygons.size());
}

TEST_CASE("OASIS and hierarchical GDSII readers: damaged files throw InvalidInput, never crash") {
    // Seeded byte flips and truncations of valid files; the fuzz target (fuzz/fuzz_oasis.cpp)
    // explores far more under the sanitizers.
    const Layout l = tiled_layout();
    const std::string oas = oasis_file(l), gds = gds_stream(l, {.hierarchy = true});
    std::uint64_t state = 12345;
    auto next = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return state >> 33;
    };
    const int trials = std::getenv("PINMASK_SANITIZED") ? 200 : 1000;
    int refused = 0;
    for (int t = 0; t < trials; ++t) {
        for (const std::string* src : {&oas, &gds}) {
            std::string b = *src;
            for (int k = 0; k < 1 + int(next() % 4); ++k) b[next() % b.size()] = char(next());
            if (next() % 4 == 0) b.resize(next() % b.size());
            try {
                (void)(src == &oas ? read_oasis(b) : read_gds(b));
            } catch (const InvalidInput&) {  // ResourceLimit is an InvalidInput
                ++refused;
            }
        }
    }
    // Any other exception type or a crash fails the case; most damaged files are refused.
    CHECK(refused > trials / 2);
}

TEST_CASE("--draw polygons: the PNG shows the drawn pinholes black, film mode shows them clear") {
    const Layout l = tiled_layout();  // clear tone: polygons are the pinholes
    const double dpi = 254;           // 100 um pixels; a pinhole is 3 pixels across
    const BoxNm b = bounding_box({l.polygons[0]});
    const auto col = int((0.5 * double(b.x0 + b.x1) - double(l.extent.x0)) / 1e5);
    const auto row = int((double(l.extent.y1) - 0.5 * double(b.y0 + b.y1)) / 1e5);
    // A point of the active area between pinholes: 0.22 mm right of the first pinhole's cell.
    const int col_gap = col + 4;
    for (DrawMode mode : {DrawMode::kFilm, DrawMode::kPolygons}) {
        const std::string path = (std::filesystem::temp_directory_path() /
                                  ("pinmask-draw-" + std::to_string(::getpid()) + ".png"))
                                     .string();
        std::ofstream(path, std::ios::binary) << png_preview(l, dpi, mode);
        const LoadedImage img = read_image(path);
        std::filesystem::remove(path);
        const double hole = img.image.channels[0](row, col) / img.full_scale;
        const double gap = img.image.channels[0](row, col_gap) / img.full_scale;
        INFO(draw_mode_name(mode) << " hole " << hole << " gap " << gap);
        if (mode == DrawMode::kFilm) {
            CHECK(hole > 0.9);  // clear pinhole in opaque film
            CHECK(gap < 0.1);
        } else {
            CHECK(hole < 0.1);  // the drawn polygon, black on white paper
            CHECK(gap > 0.9);
        }
    }
    CHECK(tone_label_line(Tone::kDark, true, "mm") == "DARK FILM POS EMUL DOWN UNIT MM");
    CHECK_THROWS_AS(parse_draw_mode("both", "--draw"), InvalidInput);
}
