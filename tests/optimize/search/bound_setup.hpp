// Shared set-up of the objective-bound tests (tests/optimize/search/test_objective_bound*.cpp): a
// box pinhole on a small period, the natural-scene prior, noise models and random patterns.
#pragma once

#include <algorithm>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "core/fft/fft.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/pattern.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/simulate/scene_prior.hpp"

namespace pinmask::test {

// The bounds are rigorous (dual values); the analytic PSNR they are compared with is a direct
// sum in double precision: round-off only (~1e-12 dB), 1e-9 dB with margin.
inline constexpr double kBoundTolDb = 1e-9;

// A box pinhole of `side` pixels on the m x m period (exact zeros among the aliases for side 3).
inline ComplexPlane box_kernel_otf(int m, int side) {
    Plane k = Plane::Zero(m, m);
    k.topLeftCorner(side, side) = 1.0 / (side * side);
    return expand_half_spectrum(Fft2(m, m).forward(k), m);
}

inline NoiseModel photons(double ppp, double read) {
    NoiseModel n;
    n.kind = NoiseKind::kPhoton;
    n.photons_per_pinhole = ppp;
    n.read_noise_e = read;
    return n;
}

inline NoiseModel gaussian(double snr_db) {
    NoiseModel n;
    n.kind = NoiseKind::kGaussianSnr;
    n.snr_db = snr_db;
    return n;
}

inline std::vector<NoiseModel> noise_models() {
    return {photons(3.0, 3.0), photons(1000.0, 2.0), gaussian(30.0), gaussian(10.0)};
}

inline std::shared_ptr<const AnalyticWienerModel> make_model(int m, int side,
                                                             const NoiseModel& noise) {
    return std::make_shared<AnalyticWienerModel>(box_kernel_otf(m, side),
                                                 natural_scene_prior(m, m, 4), noise);
}

inline Pattern random_pattern(int n, int k, std::mt19937_64& rng) {
    std::vector<int> cells(static_cast<std::size_t>(n) * n);
    std::iota(cells.begin(), cells.end(), 0);
    std::shuffle(cells.begin(), cells.end(), rng);
    Pattern p;
    p.n = n;
    for (int i = 0; i < k; ++i) p.pinholes.push_back({cells[i] / n, cells[i] % n});
    return p;
}

// The dim-light setup of tests/optimize/search/test_search_holes.cpp: paper camera, 16 x 16,
// 8 px per cell, spacing rule 2 cells; the expected PSNR over the natural-scene family (1024
// scenes of seeds 20000..) under the photon model, 3 e- per pinhole per pixel, read noise 3 e-.
inline constexpr int kDimLightN = 16;
inline constexpr int kDimLightPixelsPerCell = 8;
inline constexpr double kDimLightSpacing = 2.0;

inline Mask dim_light_template() {
    Mask tmpl;
    tmpl.camera = paper_camera();
    tmpl.pattern.n = kDimLightN;
    tmpl.pattern.min_spacing_cells = kDimLightSpacing;
    tmpl.psf.pixels_per_cell = kDimLightPixelsPerCell;
    return tmpl;
}

inline std::shared_ptr<const AnalyticWienerModel> dim_light_model() {
    const int m = kDimLightN * kDimLightPixelsPerCell;
    PriorSpec family;
    family.count = 1024;
    family.first_seed = 20000;
    return std::make_shared<AnalyticWienerModel>(
        expand_half_spectrum(
            kernel_spectrum(mask_kernel(dim_light_template()), kDimLightN, kDimLightPixelsPerCell),
            m),
        make_scene_prior(family, m), photons(3.0, 3.0));
}

}  // namespace pinmask::test
