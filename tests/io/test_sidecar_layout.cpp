// io/sidecar_layout: the layout a fabrication file is checked against, from its export sidecar
// (given settings must agree) or from the given settings alone.
#include <doctest/doctest.h>

#include <string>

#include "core/errors/error.hpp"
#include "io/sidecar_layout.hpp"

using namespace pinmask;

namespace {

io::ExportSidecar sidecar() {
    io::ExportSidecar s;
    s.tone = "dark";
    s.mirrored = true;
    s.shape = "circle";
    s.drawn_sides = 24;
    s.hole_side_m = 400e-6;
    s.chord_tolerance_m = 1e-6;
    s.frame_m = 2e-3;
    s.marks = true;
    s.label = {"line one", "line two"};
    s.max_vertices = 64;
    s.grid_nm = 5;
    s.unit = "mm";
    return s;
}

std::string message_of(const io::CheckLayoutSettings& g, const io::ExportSidecar* side) {
    try {
        io::check_layout(g, side);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("sidecar layout: every recorded setting, and agreeing settings change nothing") {
    const io::ExportSidecar s = sidecar();
    const LayoutOptions lo = io::check_layout({}, &s);
    CHECK(lo.tone == Tone::kDark);
    CHECK(lo.mirror);
    CHECK(lo.shape == HoleShape::kCircle);
    CHECK(lo.polygon_sides == 24);
    CHECK(lo.hole_side_m == 400e-6);
    CHECK(lo.chord_tolerance_m == 1e-6);
    CHECK(lo.frame_m == 2e-3);
    CHECK(lo.marks);
    CHECK(lo.label_lines == s.label);
    CHECK(lo.max_vertices == 64);
    CHECK(lo.grid_m == doctest::Approx(5e-9).epsilon(1e-15));
    io::CheckLayoutSettings g;
    g.tone = "dark";
    g.shape = "circle";
    g.frame = io::GivenLength{2e-3, "2mm"};
    g.units = "mm";
    g.mirror = true;
    const LayoutOptions same = io::check_layout(g, &s);
    CHECK(same.frame_m == lo.frame_m);
    CHECK(same.tone == lo.tone);
}

TEST_CASE("sidecar layout: a disagreeing setting names its flag; without a sidecar it applies") {
    const io::ExportSidecar s = sidecar();
    io::CheckLayoutSettings g;
    g.tone = "clear";
    CHECK(message_of(g, &s).rfind("`tone`", 0) == 0);
    g = {};
    g.frame = io::GivenLength{1e-3, "1mm"};
    CHECK(message_of(g, &s).rfind("`frame`", 0) == 0);
    g = {};
    g.units = "um";
    CHECK(message_of(g, &s).rfind("`units`", 0) == 0);
    g = {};
    g.shape = "square";
    CHECK(message_of(g, &s).find("disagrees with the export sidecar") != std::string::npos);
    // No sidecar: the given settings over the defaults (units are checked against a sidecar only).
    g.tone = "dark";
    g.units = "in";
    const LayoutOptions lo = io::check_layout(g, nullptr);
    CHECK(lo.shape == HoleShape::kSquare);
    CHECK(lo.tone == Tone::kDark);
    CHECK_FALSE(lo.marks);
}
