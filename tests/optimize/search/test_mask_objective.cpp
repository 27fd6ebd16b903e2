#include <doctest/doctest.h>

#include <memory>

#include "core/fft/fft.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/autocorrelation.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"
#include "optimize/search/mask_objective.hpp"
#include "optimize/simulate/scene_prior.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

// The objective reads the incrementally kept P^; the references recompute from scratch. Their
// only difference is FFT round-off: ~1e-15 relative, 1e-12 leaves margin.
constexpr double kSameQuantityTol = 1e-12;
// evaluate() reads the analytic PSNR from per-alias tables (optimize/metrics/aliased_wiener):
// within 1e-7 relative in MSE of the direct sum (tests/optimize/metrics/test_aliased_wiener), so <
// 5e-7 dB on a ~20 dB objective.
constexpr double kTabulatedTol = 1e-7;

Pattern small_pattern() {
    Pattern p;
    p.n = 8;
    p.pinholes = {{0, 0}, {0, 3}, {2, 6}, {5, 1}, {4, 4}};
    return p;
}

// A 4 x 4-pixel box kernel at the origin of a 32 x 32 period (n = 8, 4 px per cell).
ComplexPlane box_kernel_otf() {
    Plane k = Plane::Zero(32, 32);
    k.topLeftCorner(4, 4) = 1.0 / 16.0;
    return expand_half_spectrum(Fft2(32, 32).forward(k), 32);
}

std::shared_ptr<const AnalyticWienerModel> model() {
    NoiseModel noise;
    noise.snr_db = 30.0;
    return std::make_shared<AnalyticWienerModel>(box_kernel_otf(), natural_scene_prior(32, 32, 4),
                                                 noise);
}

}  // namespace

TEST_CASE("objective terms equal the metrics computed independently") {
    const PatternState s(small_pattern());
    ObjectiveWeights w;
    w.analytic_wiener = 1.0;
    w.max_sidelobe = 2.0;
    w.sidelobe_energy = 0.5;
    w.min_spectrum = 3.0;
    const WienerFilterSpec filter{WienerFilterKind::kOptimal, 0.0};
    const auto m = model();
    const MaskObjective objective(w, m, filter);
    const auto t = objective.terms(s);

    const ComplexPlane spectrum = pattern_spectrum(small_pattern());
    const SidelobeMetrics side = sidelobe_metrics_from_spectrum(spectrum);
    const PatternSpectrumMetrics spec = pattern_spectrum_metrics(spectrum);
    const double psnr = m->evaluate(spectrum, filter).psnr_db;
    // Reported under score's names and normalisation (the weighted terms divide by K, sqrt(K)).
    CHECK(t.at("max_sidelobe") == side.max_sidelobe);
    CHECK_CLOSE(t.at("integrated_sidelobe_level"), side.integrated_sidelobe_level,
                kSameQuantityTol);
    CHECK_CLOSE(t.at("min_abs_pattern_spectrum"), spec.min_abs_pattern_spectrum, kSameQuantityTol);
    CHECK(t.count("sidelobe_energy") == 0);
    CHECK(t.count("min_spectrum") == 0);
    // The optimal filter's figure under its name; no Wiener figure without a Wiener filter.
    CHECK_CLOSE(t.at("analytic_mmse_psnr_db"), psnr, kSameQuantityTol);
    CHECK(t.count("analytic_wiener_psnr_db") == 0);
    CHECK(analytic_figure_name(filter) == "analytic_mmse_psnr_db");
    const double expected = -psnr + 2.0 * side.max_sidelobe / 5.0 +
                            0.5 * side.integrated_sidelobe_level -
                            3.0 * spec.min_abs_pattern_spectrum / std::sqrt(5.0);
    CHECK_CLOSE(objective.evaluate(s), expected, kTabulatedTol);
    CHECK_CLOSE(t.at("objective"), expected, kTabulatedTol);
}

TEST_CASE("a tuned-NSR search reports both filters' figures under their names") {
    const PatternState s(small_pattern());
    const WienerFilterSpec tuned{WienerFilterKind::kTunedNsr, 0.0};
    const auto m = model();
    const auto t = MaskObjective(ObjectiveWeights{}, m, tuned).terms(s);
    const ComplexPlane spectrum = pattern_spectrum(small_pattern());
    const AnalyticError e = m->evaluate_tuned_nsr(spectrum);
    CHECK_CLOSE(t.at("analytic_wiener_psnr_db"), e.psnr_db, kSameQuantityTol);
    CHECK_CLOSE(t.at("analytic_wiener_nsr"), e.nsr, kSameQuantityTol);
    CHECK_CLOSE(t.at("analytic_mmse_psnr_db"),
                m->evaluate(spectrum, {WienerFilterKind::kOptimal, 0.0}).psnr_db, kSameQuantityTol);
    // No fixed NSR beats the per-frequency optimal filter.
    CHECK(t.at("analytic_mmse_psnr_db") >= t.at("analytic_wiener_psnr_db"));
    CHECK(analytic_figure_name(tuned) == "analytic_wiener_psnr_db");
}

TEST_CASE("weights are validated") {
    ObjectiveWeights w;
    w.analytic_wiener = 0.0;
    CHECK_THROWS(w.validate());
    w.max_sidelobe = -1.0;
    CHECK_THROWS(w.validate());
    ObjectiveWeights needs_model;
    CHECK_THROWS(MaskObjective(needs_model, nullptr, {}));
}
