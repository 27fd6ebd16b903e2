// The check transaction (export/pipeline/check_run): the rules are the face's overrides of the
// mask's or the vendor's, a file written from another design differs from it by the XOR area of
// the moved pinhole (its area from the shoelace formula here), the film's identity and a file
// without a unit are reported, and a mask's spacing rule is checked on the tiled pattern.
#include <doctest/doctest.h>

#include <cstdlib>

#include "export/formats/read_any.hpp"
#include "export/formats/write_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/pipeline/check_run.hpp"
#include "tests/export/export_fixtures.hpp"

using namespace pinmask;

namespace {

// Twice the signed area of a ring (shoelace), in nm^2, made positive.
double ring_area_nm2(const Ring& r) {
    double twice = 0.0;
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
        twice += double(r[j].x) * double(r[i].y) - double(r[i].x) * double(r[j].y);
    return std::abs(twice) / 2.0;
}

}  // namespace

TEST_CASE("check_mask: the face's overrides of the mask's rules, spacing on the pattern") {
    // Two pinholes one cell apart under a rule of two cells: one spacing violation.
    Mask m = pinmask::test::mask_with(4, {{0, 0}, {0, 1}});
    m.pattern.min_spacing_cells = 2.0;
    const VendorRules vendor = vendor_rules("none");
    DrcRules seen;
    const RuleOverrides overrides = [&seen](DrcRules r) {
        seen = r;
        r.max_vertices = 77;
        return r;
    };
    const CheckRun run = check_mask(m, {}, vendor, overrides, "m.mask.json");
    CHECK(run.rules.max_vertices == 77);
    CHECK(seen.min_gap_nm == rules_for_mask(m, vendor, run.check.layout.grid_nm).min_gap_nm);
    CHECK(run.check.drc.counts.count("spacing") == 1);
    CHECK_FALSE(run.check.clean());
    CHECK(run.spacing.find("2 x pitch") != std::string::npos);
    // Three cells apart in a period of four are one apart across the period's edge; four apart
    // in a period of eight are clean.
    m.pattern.pinholes = {{0, 0}, {0, 3}};
    CHECK(check_mask(m, {}, vendor, overrides, "m").check.drc.counts.count("spacing") == 1);
    Mask wide = pinmask::test::mask_with(8, {{0, 0}, {0, 4}});
    wide.pattern.min_spacing_cells = 2.0;
    CHECK(check_mask(wide, {}, vendor, overrides, "m").check.drc.counts.count("spacing") == 0);
}

TEST_CASE("check_fabrication: a file against its design, another design, no design") {
    const Mask design = pinmask::test::golden_mask();
    Mask moved = design;
    moved.pattern.pinholes[0] = {2, 0};  // disjoint from the others and from its old place
    const Layout l = make_layout(design, {});
    const auto read = [](const Mask& m) {
        return read_fabrication_bytes(write_fabrication_bytes(make_layout(m, {}), FabFormat::kGds),
                                      FabFormat::kGds);
    };
    FabricationCheckRequest q;
    q.input = "m.gds";
    q.vendor = vendor_rules("none");
    q.overrides = [](DrcRules r) { return r; };
    q.mask = &design;
    q.film = {.layer = "1/0", .layer_source = "test"};
    const CheckRun same = check_fabrication(read(design), q);
    REQUIRE(same.check.comparison);
    CHECK(same.check.comparison->identical());
    CHECK(same.check.comparison->xor_area_nm2 == 0.0);
    CHECK(same.check.identity.ok());
    CHECK(same.check.clean());
    CHECK(same.unit_assumed.empty());

    const CheckRun other = check_fabrication(read(moved), q);
    REQUIRE(other.check.comparison);
    CHECK(other.check.comparison->xor_area_nm2 ==
          doctest::Approx(2.0 * ring_area_nm2(l.polygons.at(0))).epsilon(1e-12));
    CHECK_FALSE(other.check.clean());

    // Another layer than the film's: the identity fails the check.
    q.film = {.layer = "5/0", .layer_source = "test"};
    CHECK_FALSE(check_fabrication(read(design), q).check.clean());

    // No design: no comparison, the vendor's limits with the overrides; a file without a unit.
    q.mask = nullptr;
    q.film = {.layer_source = "test"};
    q.overrides = [](DrcRules r) {
        r.min_feature_nm = 123;
        return r;
    };
    FileGeometry file = read(design);
    file.info["unit_assumed"] = "um";
    const CheckRun bare = check_fabrication(file, q);
    CHECK_FALSE(bare.check.comparison);
    CHECK(bare.rules.min_feature_nm == 123);
    CHECK(bare.rules.min_gap_nm == q.vendor.min_gap_nm);
    CHECK(bare.unit_assumed.find("read as um") != std::string::npos);
}
