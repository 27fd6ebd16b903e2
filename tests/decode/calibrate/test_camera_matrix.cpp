// The camera matrix (camera_matrix.hpp): per camera and perturbation, captures from the
// independent forward model, calibrated; the rotation and pitch errors against truth in units of
// their stated sigma, the missing pinholes found against truth, the optical density, and the
// Wiener and TV PSNR of a scene decoded with the calibrated, design and true PSFs. Each row of
// the table in docs/calibration.md is one case here (printed with --success or -s).
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>

#include "tests/decode/calibrate/camera_matrix.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Requirements of every row.
constexpr double kMaxSigmas = 4.0;          // |error| / sigma for rotation and each pitch
constexpr double kMaxLossToTrueDb = 0.5;    // calibrated PSF against the true PSF (Wiener, TV)
constexpr double kMaxLossToDesignDb = 0.0;  // calibrated never worse than the design

void run_row(const std::string& camera, const Perturbation& p) {
    const CameraCase c = camera_case(camera);
    const Mask mask = case_mask(c, p.seed + 100);
    const PointSourceScene truth = scene_of(c, mask, p);
    const Plane capture = point_source_capture(truth);
    // The dark frame: the mean dark level (an average of many dark exposures).
    const Plane dark = Plane::Constant(c.rows, c.cols, truth.dark);
    const calibrate::CalibrationSummary r = calibrate::calibrate_point_source(capture, dark, mask);
    const double e_rot = (r.rotation_deg - truth.rotation_deg) / r.rotation_sigma_deg;
    const double e_px = (r.pitch_x_px - truth.pitch_x) / r.pitch_x_sigma_px;
    const double e_py = (r.pitch_y_px - truth.pitch_y) / r.pitch_y_sigma_px;
    const std::set<Cell> found(r.missing.begin(), r.missing.end());
    // PSFs: true (the perturbed spots alone), design (no perturbation, every pinhole, same
    // centre), calibrated (the fit's).
    PointSourceScene spots = truth;
    Plane true_psf = point_source_spots(spots);
    true_psf /= true_psf.sum();
    Perturbation none;
    none.seed = p.seed;
    PointSourceScene design = scene_of(c, mask, none);
    design.missing.clear();
    Plane design_psf = point_source_spots(design);
    design_psf /= design_psf.sum();
    const DecodeScores d = decode_scores(r.psfs.full_frame, design_psf, true_psf, p.seed + 5);
    char line[400];
    std::snprintf(line, sizeof line,
                  "| %s | %.1f deg, pitch %+.1f/%+.1f %%, side %+.0f %%, %d missing, OD %s | "
                  "%+.2f | %+.2f / %+.2f | %zu of %zu | %.2f +- %.2f%s | %.1f / %.1f / %.1f | "
                  "%.1f / %.1f / %.1f |",
                  camera.c_str(), p.rotation_deg, 100 * (p.pitch_x - 1), 100 * (p.pitch_y - 1),
                  100 * (p.side - 1), p.missing,
                  std::isfinite(p.optical_density)
                      ? std::to_string(p.optical_density).substr(0, 3).c_str()
                      : "inf",
                  e_rot, e_px, e_py, found.size(), truth.missing.size(), r.optical_density,
                  r.optical_density_sigma, r.optical_density_is_bound ? " (bound)" : "",
                  d.wiener_cal, d.wiener_design, d.wiener_true, d.tv_cal, d.tv_design, d.tv_true);
    MESSAGE(line);
    CAPTURE(r.rotation_deg);
    CAPTURE(r.rotation_sigma_deg);
    CAPTURE(r.pitch_x_px);
    CAPTURE(r.pitch_y_px);
    CAPTURE(r.fit.side_scale);
    CAPTURE(r.fit.chi2_reduced);
    CAPTURE(r.background);
    CAPTURE(truth.leak);
    CAPTURE(r.fit.median_gain);
    CAPTURE(truth.amplitude);
    CAPTURE(r.fit.iterations);
    CAPTURE(r.fit.converged);
    CHECK(std::abs(e_rot) <= kMaxSigmas);
    CHECK(std::abs(e_px) <= kMaxSigmas);
    CHECK(std::abs(e_py) <= kMaxSigmas);
    CHECK(found == truth.missing);
    CHECK(r.extra_spots.empty());
    CHECK(r.optical_density >= 0.0);
    // No leak: the optical density is a lower bound, never a measured leak.
    if (!std::isfinite(p.optical_density)) CHECK(r.optical_density_is_bound);
    if (std::isfinite(p.optical_density) && !r.optical_density_is_bound)
        CHECK(std::abs(r.optical_density - p.optical_density) <=
              4 * r.optical_density_sigma + 0.05);
    CHECK(d.wiener_cal >= d.wiener_design - kMaxLossToDesignDb);
    CHECK(d.tv_cal >= d.tv_design - kMaxLossToDesignDb);
    CHECK(d.wiener_true - d.wiener_cal <= kMaxLossToTrueDb);
    CHECK(d.tv_true - d.tv_cal <= kMaxLossToTrueDb);
}

}  // namespace

// The paper's row runs by default (about 5 s); the others are slow (CTest label slow,
// tests/CMakeLists.txt: slow-calibrate-matrix-*); the six rows take about 43 s in Release.
TEST_CASE("camera matrix: paper camera rotated with pitch off and two missing at OD 2") {
    run_row("paper", {1.0, 1.006, 0.995, 1.06, 2, 2.0, 0, 11});
}

// The walkthrough's small window (examples/python/walkthrough.py: 200 x 240 px, 2 x 2 tiles of
// an 8 x 8 pattern with 6 pinholes, 9 px per cell) with spots six cells wide (main lobe +-54 px).
// Each spot's window used to be 2.5 cells, the rest of the spot in the halo held fixed on whole
// pixels: on this capture the pitch along y came out 2 % high and the rotation 2.2 deg off. Not a
// row of the table: the three PSFs decode alike (within 0.01 dB, the spots wider than the scene's
// features), and the pitch along y keeps a bias of about 3 of its sigmas (0.2 %;
// docs/calibration.md, Limits), held here to 0.4 % (about 2 s).
TEST_CASE("camera matrix: walkthrough camera with spots six cells wide in a small window") {
    const CameraCase c = camera_case("walkthrough");
    const Perturbation p{0.5, 1.004, 0.997, 1.0, 0, INFINITY, 3e6, 22};
    const Mask mask = case_mask(c, p.seed + 100);
    const PointSourceScene truth = scene_of(c, mask, p);
    const Plane dark = Plane::Constant(c.rows, c.cols, truth.dark);
    const calibrate::CalibrationSummary r =
        calibrate::calibrate_point_source(point_source_capture(truth), dark, mask);
    CAPTURE(r.rotation_deg);
    CAPTURE(r.rotation_sigma_deg);
    CAPTURE(r.pitch_x_px);
    CAPTURE(r.pitch_y_px);
    CAPTURE(r.pitch_x_sigma_px);
    CAPTURE(r.pitch_y_sigma_px);
    CAPTURE(r.fit.chi2_reduced);
    CHECK(std::abs(r.rotation_deg - truth.rotation_deg) <= kMaxSigmas * r.rotation_sigma_deg);
    CHECK(std::abs(r.pitch_x_px - truth.pitch_x) <= kMaxSigmas * r.pitch_x_sigma_px);
    CHECK(std::abs(r.pitch_y_px / truth.pitch_y - 1) <= 0.004);
    CHECK(r.missing.empty());
    CHECK(r.extra_spots.empty());
    CHECK(r.fit.chi2_reduced < 1.2);
}

TEST_CASE("camera matrix: C-mount at 2 degrees with side -10 % and three missing" *
          doctest::skip()) {
    run_row("c-mount", {2.0, 0.992, 1.004, 0.9, 3, 1.5, 0, 12});
}

TEST_CASE("camera matrix: NIR camera with spots one cell wide in the issue's capture" *
          doctest::skip()) {
    run_row("nir", {1.0, 1.008, 1.008, 1.0, 0, INFINITY, 0, 14});
}

TEST_CASE("camera matrix: lensless with pitch -1 % and one missing at OD 2" * doctest::skip()) {
    run_row("lensless", {0.0, 0.99, 0.99, 1.0, 1, 2.0, 0, 16});
}

TEST_CASE("camera matrix: phone-like 1.12 um sensor with spots wider than a cell" *
          doctest::skip()) {
    run_row("phone", {0.5, 1.01, 1.01, 1.1, 1, INFINITY, 0, 18});
}

TEST_CASE("camera matrix: NIR camera at -1.5 degrees with the side 8 % small and two missing" *
          doctest::skip()) {
    run_row("nir", {-1.5, 0.99, 1.005, 0.92, 2, 2.0, 0, 20});
}
