// What identifies the film (export/pipeline/film_identity): the layers the readers record, written
// by the writers with chosen layers (GDSII, OASIS, DXF), and the comparison on geometry built
// here by hand, so each rule is checked apart from the readers.
#include <doctest/doctest.h>

#include "export/formats/read_any.hpp"
#include "export/formats/write_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/pipeline/film_identity.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;

TEST_CASE("the readers record the layers the writers drew on") {
    const Layout l = make_layout(pinmask::test::golden_mask(), {});
    WriteOptions w;
    w.gds = {.layer = 7, .datatype = 3};
    w.dxf = {.layer = "FILM_A"};
    for (FabFormat f : {FabFormat::kGds, FabFormat::kOasis, FabFormat::kDxf}) {
        INFO(fab_format_name(f));
        const FileGeometry g = read_fabrication_bytes(write_fabrication_bytes(l, f, w), f);
        CHECK(g.layers == std::vector<std::string>{f == FabFormat::kDxf ? "FILM_A" : "7/3"});
    }
    // Gerber and SVG have no layers.
    CHECK(read_fabrication_bytes(write_fabrication_bytes(l, FabFormat::kGerber, w),
                                 FabFormat::kGerber)
              .layers.empty());
}

TEST_CASE("film identity: one layer as expected, another layer, two layers, not known") {
    FileGeometry g;
    g.layers = {"1/0"};
    FilmIdentityExpected e{.layer = "1/0", .layer_source = "the sidecar"};
    CHECK(check_film_identity(g, FabFormat::kGds, e).ok());
    g.layers = {"5/0"};
    const FilmIdentity other = check_film_identity(g, FabFormat::kOasis, e);
    REQUIRE(other.items.size() == 1);
    CHECK_FALSE(other.ok());
    CHECK(other.items[0].what == "OASIS layer/datatype");
    CHECK(other.items[0].message.find("geometry on layer 5/0, not 1/0") != std::string::npos);
    g.layers = {"1/0", "2/0"};
    CHECK_FALSE(check_film_identity(g, FabFormat::kGds, e).ok());
    // Two layers fail even when nothing is expected; one layer is then not known, not failed.
    const FilmIdentityExpected none{.layer_source = "no sidecar"};
    CHECK_FALSE(check_film_identity(g, FabFormat::kDxf, none).ok());
    g.layers = {"MASK"};
    const FilmIdentity unknown = check_film_identity(g, FabFormat::kDxf, none);
    CHECK(unknown.ok());
    REQUIRE(unknown.not_known().size() == 1);
    CHECK(unknown.not_known()[0]->found == "MASK");
    // No layer items for formats without layers.
    CHECK(check_film_identity(g, FabFormat::kSvg, e).items.empty());
}

TEST_CASE("film identity: Gerber polarity against the tone and the file's own comment") {
    FileGeometry g;
    g.info = {{"polarity", "Negative"}, {"tone", "clear"}};
    FilmIdentityExpected e{.tone = Tone::kClear, .tone_source = "the sidecar"};
    CHECK(check_film_identity(g, FabFormat::kGerber, e).ok());
    e.tone = Tone::kDark;
    CHECK_FALSE(check_film_identity(g, FabFormat::kGerber, e).ok());
    g.info = {{"polarity", "Positive"}, {"tone", "clear"}};
    const FilmIdentityExpected none{.tone_source = "no sidecar"};
    const FilmIdentity own = check_film_identity(g, FabFormat::kGerber, none);
    CHECK_FALSE(own.ok());  // contradicts its own comment
    CHECK(own.items[0].message.find("contradicts") != std::string::npos);
    g.info = {{"tone", "clear"}};  // no polarity stated
    CHECK(check_film_identity(g, FabFormat::kGerber, none).ok());
    e.tone = Tone::kClear;
    CHECK_FALSE(check_film_identity(g, FabFormat::kGerber, e).ok());
}

TEST_CASE("film identity: a file without geometry has no layer to compare, and says so") {
    const FileGeometry empty;
    const FilmIdentity id = check_film_identity(
        empty, FabFormat::kGds, FilmIdentityExpected{.layer = "1/0", .layer_source = "sidecar"});
    REQUIRE(id.items.size() == 1);
    CHECK(id.items[0].found == "none");
    CHECK(id.items[0].message == "no geometry whose layer could be compared");
}
