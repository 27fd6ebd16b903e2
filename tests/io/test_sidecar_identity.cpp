// What a fabrication file should be (io/sidecar_identity): from the export sidecar's entry for
// the file, else from a vendor preset and a tone given to check; otherwise not known, with why.
#include <doctest/doctest.h>

#include "core/errors/error.hpp"
#include "io/export_sidecar.hpp"
#include "io/sidecar_identity.hpp"

using namespace pinmask;
using io::film_identity_expected;

TEST_CASE("the sidecar's entry for the file gives the layer, its tone the polarity") {
    io::ExportSidecar side;
    side.tone = "dark";
    side.files = {{.name = "m.gds", .format = "gds", .detail = "layer 7/3"},
                  {.name = "m.dxf", .format = "dxf", .detail = "layer FILM"},
                  {.name = "m.svg", .format = "svg"}};
    const auto gds = film_identity_expected("fab/m.gds", &side, "fab/m.export.json", false,
                                            std::nullopt, std::nullopt);
    CHECK(gds.layer == "7/3");
    CHECK(gds.layer_source == "the export sidecar m.export.json");
    CHECK(gds.tone == Tone::kDark);
    CHECK(film_identity_expected("fab/m.dxf", &side, "fab/m.export.json", false, std::nullopt,
                                 std::nullopt)
              .layer == "FILM");
    // A file the sidecar lists without a layer (or not at all): the layer is not known.
    const auto oas = film_identity_expected("fab/m.oas", &side, "fab/m.export.json", false,
                                            std::nullopt, std::nullopt);
    CHECK_FALSE(oas.layer);
    CHECK(oas.layer_source.find("lists no layer for m.oas") != std::string::npos);
}

TEST_CASE("without a sidecar: a vendor preset's default layers and tone, a given tone, or none") {
    const auto preset = film_identity_expected("m.dxf", nullptr, "m.export.json", false,
                                               std::string("film-plotter"), std::nullopt);
    CHECK(preset.layer == "PINMASK");
    CHECK(preset.tone == Tone::kClear);
    CHECK(film_identity_expected("m.gds", nullptr, "m.export.json", false,
                                 std::string("chrome-photomask"), std::nullopt)
              .layer == "1/0");
    // A rule name is no preset: nothing said about the layer.
    const auto rules = film_identity_expected("m.gds", nullptr, "m.export.json", false,
                                              std::string("film"), std::nullopt);
    CHECK_FALSE(rules.layer);
    CHECK_FALSE(rules.tone);
    CHECK(rules.layer_source == "no export sidecar m.export.json and no vendor preset given");
    // The tone given wins over the preset's.
    const auto toned = film_identity_expected("m.gbr", nullptr, "m.export.json", false,
                                              std::string("gerber-film"), std::string("dark"));
    CHECK(toned.tone == Tone::kDark);
    CHECK(toned.tone_source == "the tone given to check");
    CHECK_THROWS_AS(film_identity_expected("m.gds", nullptr, "m.export.json", false,
                                           std::string("bogus"), std::nullopt),
                    InvalidInput);
}
