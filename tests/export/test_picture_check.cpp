// Picture checks inside the library: the SVG's two drawings (--draw film|polygons)
// read back, the pictures check reads (1-bit TIFF, PNG, PDF) compared with their design and
// caught when they differ, and the window dictionary of hierarchical GDSII: exact (expands to
// the same placements, flattens to the same rings as flat GDSII) and at least 5x smaller than
// flat GDSII on the 1024 x 1024-cell, 100k-pinhole jittered lattice of the export bench.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <tuple>

#include "core/errors/error.hpp"
#include "export/formats/gds_reader.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/pdf_reader.hpp"
#include "export/formats/pdf_writer.hpp"
#include "export/formats/plotter_raster.hpp"
#include "export/formats/png_preview.hpp"
#include "export/formats/svg_reader.hpp"
#include "export/formats/svg_writer.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/window_cells.hpp"
#include "export/pipeline/file_check.hpp"
#include "export/pipeline/raster_check.hpp"
#include "export/pipeline/read_back.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;
using pinmask::test::golden_mask;

namespace {

// 8 x 8 cells of 440 um, 2 x 2 tiles, four pinholes, marks, label, a frame: ~8 mm of film.
Layout picture_layout(Tone tone = Tone::kClear, HoleShape shape = HoleShape::kSquare) {
    Mask m = golden_mask();
    m.pattern.n = 8;
    m.pattern.pinholes = {{0, 0}, {2, 3}, {5, 6}, {7, 1}};
    m.pattern.tiles_rows = m.pattern.tiles_cols = 2;
    LayoutOptions o;
    o.tone = tone;
    o.shape = shape;
    o.hole_side_m = 301.3e-6;
    o.frame_m = 500e-6;
    o.marks = true;
    o.label_lines = default_label_lines(m, "p");
    return make_layout(m, o);
}

std::filesystem::path temp_file(const std::string& name) {
    return std::filesystem::temp_directory_path() /
           ("pinmask-picture-" + std::to_string(::getpid()) + "-" + name);
}

void write_file(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
}

// The bench's jittered lattice (bench/export_bench): one pinhole in each 3 x 3 block at a random
// corner of its top-left 2 x 2, kept with probability 0.86; 20 um cells.
Mask jittered_mask(int n, std::uint64_t seed) {
    Mask m;
    m.camera.pinhole_m = 20e-6;
    m.pattern.n = n;
    m.pattern.tiles_rows = m.pattern.tiles_cols = 1;  // untiled: no tile array to help
    m.pattern.min_spacing_cells = 2.0;
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution keep(0.86), half(0.5);
    for (int r = 0; r + 2 < n; r += 3)
        for (int c = 0; c + 2 < n; c += 3)
            if (keep(rng)) m.pattern.pinholes.push_back({r + half(rng), c + half(rng)});
    return m;
}

bool placement_less(const Placement& a, const Placement& b) {
    return std::tie(a.shape, a.at.x, a.at.y) < std::tie(b.shape, b.at.x, b.at.y);
}

}  // namespace

TEST_CASE("SVG --draw film: opaque plate and white clear areas, read back as the drawn rings") {
    for (Tone tone : {Tone::kClear, Tone::kDark}) {
        const Layout l = picture_layout(tone);
        const std::string film = svg_document(l, DrawMode::kFilm);
        const std::string polys = svg_document(l, DrawMode::kPolygons);
        CHECK(film.find("draw=film") != std::string::npos);
        CHECK(polys.find("draw=polygons") != std::string::npos);
        // Clear tone: the film has the plate and white rings; dark tone draws the same rings.
        const bool clear = tone == Tone::kClear;
        CHECK((film.find(kSvgFilmGroup) != std::string::npos) == clear);
        CHECK((film.find("fill=\"#ffffff\"") != std::string::npos) == clear);
        CHECK(polys.find(kSvgFilmGroup) == std::string::npos);
        for (const std::string* doc : {&film, &polys}) {
            const ReadBack r = compare_with_layout(read_svg(*doc), l);
            CHECK(r.identical());
            CHECK(r.hash_ok());
        }
    }
    // A plate that is not the extent, or a plate in a drawing not marked draw=film, is refused.
    const Layout l = picture_layout();
    std::string film = svg_document(l, DrawMode::kFilm);
    const std::size_t plate = film.find("<path d=\"", film.find(kSvgFilmGroup)) + 9;
    std::string shrunk = film;
    shrunk.replace(plate, film.find('"', plate) - plate, "M0,0L1,0L1,-1L0,-1Z");
    CHECK_THROWS_AS(read_svg(shrunk), InvalidInput);
    std::string unmarked = film;
    unmarked.replace(unmarked.find("draw=film"), 9, "draw=xxxx");
    CHECK_THROWS_AS(read_svg(unmarked), InvalidInput);
    // A clear-tone film drawing that lost its plate group is refused too.
    std::string no_plate = film;
    no_plate.replace(no_plate.find(kSvgFilmGroup), std::string(kSvgFilmGroup).size(), "other");
    CHECK_THROWS_AS(read_svg(no_plate), InvalidInput);
}

TEST_CASE("1-bit TIFF read back equals the design's raster; a changed pixel or design is caught") {
    const Layout l = picture_layout();
    const double dpi = 2540;  // 10 um pixels: the 301.3 um squares are 30 pixels wide
    const auto path = temp_file("t.tif");
    write_file(path, plotter_tiff(l, dpi, 0));
    const RasterPicture pic = read_tiff1_file(path);
    CHECK(pic.dpi == doctest::Approx(dpi));
    CHECK(pic.info.at("hash") == l.mask_hash);
    const RasterComparison ok = compare_raster(pic, l, DrawMode::kFilm, 0);
    CHECK(ok.ok());
    CHECK(ok.differing == 0);
    CHECK(plotter_raster(l, dpi).cols == pic.cols);
    // One flipped pixel in the middle of a pinhole is beyond any edge.
    RasterPicture flipped = pic;
    const Ring& hole = l.polygons[0];
    const BoxNm b = bounding_box({hole});
    const double pixel = 25.4e6 / dpi;
    const auto col = std::int64_t((0.5 * double(b.x0 + b.x1) - double(l.extent.x0)) / pixel);
    const auto row = std::int64_t((double(l.extent.y1) - 0.5 * double(b.y0 + b.y1)) / pixel);
    CHECK_FALSE(pic.at(row, col));  // clear
    flipped.bits[std::size_t(row) * flipped.stride() + std::size_t(col / 8)] ^=
        std::uint8_t(0x80 >> (col % 8));
    const RasterComparison bad = compare_raster(flipped, l, DrawMode::kFilm, 0);
    CHECK(bad.differing == 1);
    CHECK_FALSE(bad.ok());
    // The dark-tone design is not this file.
    CHECK_FALSE(compare_raster(pic, picture_layout(Tone::kDark), DrawMode::kFilm, 0).ok());
    // A file at another dpi has another size.
    RasterPicture other = pic;
    other.dpi = 2 * dpi;
    CHECK_FALSE(compare_raster(other, l, DrawMode::kFilm, 0).same_size());
    std::filesystem::remove(path);
    CHECK_THROWS_AS(read_tiff1_file(temp_file("missing.tif")), InvalidInput);
}

TEST_CASE("PNG preview against the design within one pixel of an edge, both draw modes") {
    for (Tone tone : {Tone::kClear, Tone::kDark})
        for (DrawMode draw : {DrawMode::kFilm, DrawMode::kPolygons}) {
            const Layout l = picture_layout(tone, HoleShape::kCircle);
            const double dpi = 1000;  // 25.4 um pixels: pinholes ~12 pixels across
            const RasterPicture pic = read_png_bytes(png_preview(l, dpi, draw), dpi);
            const RasterComparison c = compare_raster(pic, l, draw, kRasterEdgePixels);
            INFO(tone_name(tone) << " " << draw_mode_name(draw) << ": " << c.describe());
            CHECK(c.ok());
            // The other drawing of a clear-tone layout is a different picture.
            if (tone == Tone::kClear) {
                const DrawMode other =
                    draw == DrawMode::kFilm ? DrawMode::kPolygons : DrawMode::kFilm;
                CHECK_FALSE(compare_raster(pic, l, other, kRasterEdgePixels).ok());
            }
        }
    // A design with one pinhole fewer: its interior pixels differ beyond the edges.
    const Layout l = picture_layout();
    Layout fewer = l;
    fewer.polygons.erase(fewer.polygons.begin());
    const RasterPicture pic = read_png_bytes(png_preview(l, 1000, DrawMode::kFilm), 1000);
    const RasterComparison c = compare_raster(pic, fewer, DrawMode::kFilm, kRasterEdgePixels);
    CHECK(c.beyond_edges > 0);
    CHECK_FALSE(c.ok());
    CHECK_THROWS_AS(read_png_bytes("not a png", 100), InvalidInput);
}

TEST_CASE("PDF read back: the page's filled paths match the design within 1/256 pt") {
    for (Tone tone : {Tone::kClear, Tone::kDark})
        for (DrawMode draw : {DrawMode::kFilm, DrawMode::kPolygons})
            for (HoleShape shape : {HoleShape::kSquare, HoleShape::kCircle}) {
                const Layout l = picture_layout(tone, shape);
                PdfOptions o;
                o.draw = draw;
                const PdfPage page = read_pdf_page(pdf_document(l, o));
                const PdfComparison c = compare_pdf(page, l, o);
                INFO(tone_name(tone) << " " << draw_mode_name(draw) << ": " << c.describe());
                CHECK(c.ok());
                CHECK(c.max_deviation_nm <= kPdfToleranceNm);
                CHECK(c.rings == c.expected_rings);
            }
    // A design with one pinhole moved by 5 um (> 1.38 um) is found; so is another draw mode.
    const Layout l = picture_layout();
    Layout moved = l;
    for (PointNm& p : moved.polygons[1]) p.x += 5000;
    const PdfPage page = read_pdf_page(pdf_document(l, {}));
    const PdfComparison c = compare_pdf(page, moved, {});
    CHECK(c.beyond_tolerance == 1);
    CHECK(c.max_deviation_nm > 5000 - kPdfToleranceNm);
    CHECK(c.max_deviation_nm < 5000 + kPdfToleranceNm);
    CHECK_FALSE(c.ok());
    CHECK_FALSE(compare_pdf(page, l, {.draw = DrawMode::kPolygons}).ok());
    CHECK_FALSE(compare_pdf(page, l, {.margin_m = 5e-3}).ok());  // another page size
    // Not a PDF, a truncated one, an unknown operator: InvalidInput.
    const std::string pdf = pdf_document(l, {});
    CHECK_THROWS_AS(read_pdf_page("hello"), InvalidInput);
    CHECK_THROWS_AS(read_pdf_page(pdf.substr(0, pdf.size() / 3)), InvalidInput);
}

TEST_CASE("check_picture_file: every picture export writes is clean against its design") {
    const Layout l = picture_layout(Tone::kDark);
    const auto tif = temp_file("c.tif"), png = temp_file("c.png"), pdf = temp_file("c.pdf");
    write_file(tif, plotter_tiff(l, 2540, 0));
    write_file(png, png_preview(l, 1200, DrawMode::kPolygons));
    write_file(pdf, pdf_document(l, {.draw = DrawMode::kPolygons}));
    PictureCheckOptions o;
    o.draw = DrawMode::kPolygons;
    o.png_dpi = 1200;
    for (const auto& p : {tif, png, pdf}) {
        const FileCheck c = check_picture_file(p, l, o);
        INFO(p.string() << ": " << c.picture->result);
        CHECK(c.picture->ok);
        CHECK(c.clean());
    }
    o.png_dpi = 0;  // unknown dpi: refused, not guessed
    CHECK_THROWS_AS(check_picture_file(png, l, o), InvalidInput);
    for (const auto& p : {tif, png, pdf}) std::filesystem::remove(p);
}

TEST_CASE("GDSII window cells: exact, and >= 5x smaller than flat on the 100k jittered lattice") {
    const Mask m = jittered_mask(1024, 1);
    const Layout l = make_layout(m, {});
    REQUIRE(l.polygons.size() > 99'000);
    REQUIRE(l.tiles_rows * l.tiles_cols == 1);
    const Repetition rep = find_repetition(l.polygons, l.active_area, 1, 1);
    const WindowCells w = find_window_cells(rep.placements, {});
    CHECK(w.w > 0);  // windows pay on this pattern
    std::vector<Placement> a = expand_windows(w), b = rep.placements;
    std::sort(a.begin(), a.end(), placement_less);
    std::sort(b.begin(), b.end(), placement_less);
    CHECK(a.size() == b.size());
    CHECK(std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
        return x.shape == y.shape && x.at == y.at;
    }));
    const std::string flat = gds_stream(l, {});
    const std::string cells = gds_stream(l, {.hierarchy = true});
    const FileGeometry gf = read_gds(flat), gc = read_gds(cells);
    const ReadBack same = compare_rings(gc.rings, gf.rings, "", "");
    CHECK(same.identical());
    CHECK(same.xor_area_nm2 == 0);
    CHECK(compare_with_layout(gc, l).identical());
    MESSAGE("flat " << flat.size() << " bytes, hierarchical " << cells.size() << " bytes");
    CHECK(double(flat.size()) >= 5.0 * double(cells.size()));
    // A uniformly random pattern (no lattice structure to share) still flattens exactly.
    const Layout u = make_layout(test::random_dense_mask(64, 0.1, 7), {});
    CHECK(compare_with_layout(read_gds(gds_stream(u, {.hierarchy = true})), u).identical());
}
