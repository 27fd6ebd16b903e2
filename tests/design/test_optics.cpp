#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "design/optics/optics.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// The paper quotes its figures rounded; a figure printed with its last digit at 10^e matches when
// |ours - quoted| <= half of 10^e. One named bound per published precision:
constexpr double kHalfUnit3rdDecimalMm = 0.0005e-3;  // 0.271 mm, 0.238 mm, 0.242 mm
constexpr double kHalfUnit1stDecimalMm = 0.05e-3;    // 101.5 mm
constexpr double kHalfUnit1stDecimal = 0.05;         // N_F = 1.6, u_min = 12.9 m
constexpr double kHalfUnit2ndDecimal = 0.005;        // N_F = 0.87, 7.94 px, 8.08 px
constexpr double kHalfUnitUm = 0.5e-6;               // 443 um
// "about 2 pixels": the paper's mismatch at u = 6 m, stated to the nearest pixel.
constexpr double kAboutOnePixel = 0.5;
// Exact relations evaluated in double: a few roundings.
constexpr double kExactRel = 1e-14;

OpticsReport paper() { return compute_optics(paper_camera(), PatternGeometry{}); }

}  // namespace

TEST_CASE("paper preset reproduces the published figures") {
    const OpticsReport r = paper();
    CHECK(std::fabs(r.optimum_pinhole_m - 0.271e-3) <= kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(r.fresnel_number - 1.6) <= kHalfUnit1stDecimal);
    CHECK(std::fabs(r.effective_distance_m - 101.5e-3) <= kHalfUnit1stDecimalMm);
    CHECK(std::fabs(r.fresnel_number_with_lens - 0.87) <= kHalfUnit2ndDecimal);
    CHECK(std::fabs(r.geometric_spot_m - 0.238e-3) <= kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(r.pixels_per_cell_at_inf - 7.94) <= kHalfUnit2ndDecimal);
    CHECK(std::fabs(r.geometric_spot_at_u_m - 0.242e-3) <= kHalfUnit3rdDecimalMm);
    CHECK(std::fabs(r.pixels_per_cell_at_u - 8.08) <= kHalfUnit2ndDecimal);
    CHECK(r.integer_pixels_per_cell == 8);
    CHECK(std::fabs(r.pinhole_for_integer_pixels_m - 443e-6) <= kHalfUnitUm);
    CHECK_CLOSE(r.max_separation_m, 7.04e-3, kExactRel);
    CHECK(std::fabs(r.lsi_min_object_distance_m - 12.9) <= kHalfUnit1stDecimal);
    CHECK(std::fabs(r.lsi_mismatch_px - 2.0) <= kAboutOnePixel);
    CHECK_FALSE(r.is_shift_invariant());
    CHECK(r.psf_size_px == 128);
    CHECK_CLOSE(r.periods_on_sensor_cols, 720.0 / 128, kExactRel);
    CHECK_CLOSE(r.periods_on_sensor_rows, 480.0 / 128, kExactRel);
    CHECK_CLOSE(r.mask_width_m, 14.08e-3, kExactRel);
    CHECK_CLOSE(r.open_fraction, 20.0 / 256, kExactRel);
    CHECK(r.light_gain == 20);
    CHECK(r.kernel_model == KernelModel::kFresnel);
    CHECK(contains(r.kernel_reason, "auto"));
}

TEST_CASE("relations hold exactly: magnification, z_eff(u), N(u), pixel counts") {
    Camera c = paper_camera();
    c.object_distance_m = 2.5;
    const OpticsReport r = compute_optics(c, PatternGeometry{});
    const double f = c.sensor_distance_m, fp = c.lens_focal_m, u = c.object_distance_m;
    CHECK_CLOSE(r.magnification, 1 - f / fp, kExactRel);
    CHECK_CLOSE(r.magnification_at_u, 1 - f / fp + f / u, kExactRel);
    CHECK_CLOSE(r.effective_distance_m, f * fp / (fp - f), kExactRel);
    CHECK_CLOSE(1 / r.effective_distance_at_u_m, 1 / f - (1 / fp - 1 / u), kExactRel);
    CHECK_CLOSE(r.fresnel_number_with_lens_at_u,
                c.pinhole_m * c.pinhole_m / (4 * c.wavelength_m * r.effective_distance_at_u_m),
                kExactRel);
    // The magnification of the Fresnel pattern equals the cell-pitch factor: f / z_eff(u).
    CHECK_CLOSE(r.magnification_at_u, f / r.effective_distance_at_u_m, kExactRel);
    CHECK_CLOSE(r.pixels_per_cell_at_u, r.magnification_at_u * c.pinhole_m / c.pixel_pitch_m,
                kExactRel);
    CHECK_CLOSE(r.lsi_mismatch_px, f * 16 * c.pinhole_m / (u * c.pixel_pitch_m), kExactRel);
    CHECK(r.is_shift_invariant() == (u >= r.lsi_min_object_distance_m));
}

TEST_CASE("u = inf: no mismatch, design and at-u figures coincide") {
    Camera c = paper_camera();
    c.object_distance_m = std::numeric_limits<double>::infinity();
    const OpticsReport r = compute_optics(c, PatternGeometry{});
    CHECK(r.lsi_mismatch_px == 0.0);
    CHECK(r.is_shift_invariant());
    CHECK(r.magnification_at_u == r.magnification);
    CHECK(r.effective_distance_at_u_m == r.effective_distance_m);
    CHECK(r.fresnel_number_with_lens_at_u == r.fresnel_number_with_lens);
}

TEST_CASE("f = f' is the Fraunhofer limit: infinite z_eff, no NaN anywhere") {
    Camera c = paper_camera();
    c.lens_focal_m = c.sensor_distance_m;
    for (double u : {6.0, std::numeric_limits<double>::infinity()}) {
        c.object_distance_m = u;
        const OpticsReport r = compute_optics(c, PatternGeometry{});
        CHECK(std::isinf(r.effective_distance_m));
        CHECK(r.effective_distance_m > 0);
        CHECK(r.fresnel_number_with_lens == 0.0);
        CHECK(r.magnification == 0.0);
        CHECK(r.geometric_spot_m == 0.0);
        CHECK(std::isinf(r.pinhole_for_integer_pixels_m));
        CHECK(r.integer_pixels_per_cell == 1);
        CHECK(r.kernel_model == KernelModel::kFraunhofer);
        for (double x :
             {r.pixels_per_cell_at_inf, r.pixels_per_cell_at_u, r.fresnel_number_with_lens_at_u,
              r.lsi_min_object_distance_m, r.lsi_mismatch_px, r.optimum_pinhole_m}) {
            CHECK(std::isfinite(x));
        }
    }
}

TEST_CASE("f > f' is past focus: negative z_eff and magnification, positive sizes") {
    Camera c = paper_camera();
    c.sensor_distance_m = 0.2;
    const OpticsReport r = compute_optics(c, PatternGeometry{});
    CHECK_CLOSE(r.effective_distance_m, 0.2 * 0.12 / (0.12 - 0.2), kExactRel);
    CHECK(r.magnification < 0);
    CHECK_CLOSE(r.geometric_spot_m, (0.2 / 0.12 - 1) * c.pinhole_m, kExactRel);
    CHECK(r.fresnel_number_with_lens > 0);
    CHECK(r.pinhole_for_integer_pixels_m > 0);
}

TEST_CASE("no lens (f' = inf): z_eff = f and N_F with lens = N_F") {
    Camera c = paper_camera();
    c.lens_focal_m = std::numeric_limits<double>::infinity();
    const OpticsReport r = compute_optics(c, PatternGeometry{});
    CHECK_CLOSE(r.effective_distance_m, c.sensor_distance_m, kExactRel);
    CHECK_CLOSE(r.fresnel_number_with_lens, r.fresnel_number, kExactRel);
    CHECK(r.magnification == 1.0);
}

TEST_CASE("a requested model is reported as requested") {
    const OpticsReport r =
        compute_optics(paper_camera(), PatternGeometry{}, KernelModel::kBox, OpticsOptions{});
    CHECK(r.kernel_model == KernelModel::kBox);
    CHECK(r.kernel_reason == "requested");
    const OpticsReport fig = compute_optics(paper_camera(), PatternGeometry{},
                                            KernelModel::kPaperFig3b, OpticsOptions{});
    CHECK(contains(fig.kernel_reason, "Fig. 3b"));
}

TEST_CASE("nonsense input is InvalidInput naming the field") {
    auto fails_naming = [](Camera c, PatternGeometry g, OpticsOptions o, const std::string& field) {
        try {
            compute_optics(c, g, KernelModel::kAuto, o);
            FAIL("no exception for " << field);
        } catch (const InvalidInput& e) {
            CHECK(contains(std::string(e.what()), field));
        }
    };
    Camera c = paper_camera();
    c.sensor_distance_m = 0;
    fails_naming(c, {}, {}, "sensor_distance_m");
    c = paper_camera();
    c.wavelength_m = std::nan("");
    fails_naming(c, {}, {}, "wavelength_m");
    c = paper_camera();
    c.lens_focal_m = -0.1;
    fails_naming(c, {}, {}, "lens_focal_m");
    fails_naming(paper_camera(), PatternGeometry{0, 0, 1, 1}, {}, "grid");
    fails_naming(paper_camera(), PatternGeometry{4, 17, 1, 1}, {}, "holes");
    fails_naming(paper_camera(), PatternGeometry{4, 3, 0, 1}, {}, "tiles");
    fails_naming(paper_camera(), {}, OpticsOptions{0.0}, "lsi_tolerance_px");
}

TEST_CASE("a 1 x 1 grid and a full grid are legal") {
    const OpticsReport one = compute_optics(paper_camera(), PatternGeometry{1, 1, 1, 1});
    CHECK(one.psf_size_px == 8);
    CHECK(one.open_fraction == 1.0);
    const OpticsReport none = compute_optics(paper_camera(), PatternGeometry{3, 0, 1, 1});
    CHECK(none.light_gain == 0.0);
}
