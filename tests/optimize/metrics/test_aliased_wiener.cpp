// The O(n^2) analytic objective (optimize/metrics/aliased_wiener) against the direct O(m^2) sum of
// optimize/metrics/analytic_error on a spectrum recomputed from scratch, after many random moves.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/aliased_wiener.hpp"
#include "optimize/search/mask_objective.hpp"
#include "optimize/search/pattern_state.hpp"
#include "optimize/simulate/scene_prior.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

namespace {

// Cubic Hermite interpolation at step 1/16 in u of sums of unit-width steps: the bound
// h^4 max|f''''| / 384 is ~2e-8 of each sum; measured up to 1.7e-9 relative on the MSE over
// these walks (printed), 1e-7 is the bound with margin.
constexpr double kTabulationTol = 1e-7;
// Tuned NSR: the reference (AnalyticWienerModel::evaluate_tuned_nsr) stops its golden section
// within kTuneToleranceLog10 = 0.01 decade of the minimum, where the MSE curve is flat to ~1e-5
// relative; the aliased grid parabola is closer to the minimum than that. Measured up to
// 2.7e-5 relative (printed); 1e-4 is the bound with margin.
constexpr double kTunedTol = 1e-4;
// Frequencies outside the tables are the same sums in another order: round-off only.
constexpr double kExactSumTol = 1e-12;

constexpr int kN = 8, kPpc = 5, kM = kN * kPpc;

// A 3 x 3-pixel box pinhole on the 40 x 40 period: |K^|^2 has exact zeros among the aliases.
ComplexPlane box_kernel_otf() {
    Plane k = Plane::Zero(kM, kM);
    k.topLeftCorner(3, 3) = 1.0 / 9.0;
    return expand_half_spectrum(Fft2(kM, kM).forward(k), kM);
}

std::shared_ptr<const AnalyticWienerModel> model(const NoiseModel& noise) {
    return std::make_shared<AnalyticWienerModel>(box_kernel_otf(), natural_scene_prior(kM, kM, 4),
                                                 noise);
}

NoiseModel dim_photons() {
    NoiseModel n;
    n.kind = NoiseKind::kPhoton;
    n.photons_per_pinhole = 3.0;
    n.read_noise_e = 3.0;
    return n;
}

Pattern start() {
    Pattern p;
    p.n = kN;
    p.pinholes = {{0, 0}, {0, 3}, {2, 6}, {5, 1}, {4, 4}, {6, 6}};
    return p;
}

// Random legal moves, adds and removes; after each, the aliased MSE of the incrementally kept
// spectrum against the direct sum on the spectrum recomputed from the pattern.
void check_random_walk(const std::shared_ptr<const AnalyticWienerModel>& m,
                       const WienerFilterSpec& filter, double tol, bool recompute = true) {
    const AliasedWiener fast(m, kN, filter);
    PatternState state(start());
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<int> cell(0, kN - 1), kind(0, 9);
    int checked = 0;
    double worst = 0.0;
    for (int step = 0; step < 400; ++step) {
        const Cell to{cell(rng), cell(rng)};
        const int what = kind(rng);
        if (what == 0 && state.can_add(to)) {
            state.add(to);
        } else if (what == 1 && state.holes() > 1) {
            state.remove(std::uniform_int_distribution<int>(0, state.holes() - 1)(rng));
        } else {
            const int j = std::uniform_int_distribution<int>(0, state.holes() - 1)(rng);
            if (!state.is_legal_move(j, to)) continue;
            state.move(j, to);
        }
        const AnalyticError got = fast.evaluate(state.spectrum());
        const AnalyticError want =
            m->evaluate(recompute ? pattern_spectrum(state.pattern()) : state.spectrum(), filter);
        const int holes = state.holes();
        CAPTURE(step);
        CAPTURE(holes);
        CHECK_CLOSE(got.mse, want.mse, tol);
        worst = std::max(worst, std::fabs(got.mse - want.mse) / want.mse);
        CHECK_CLOSE(got.mean_square_capture, want.mean_square_capture, kExactSumTol * 1e3);
        CHECK_CLOSE(got.noise_variance, want.noise_variance, kExactSumTol * 1e3);
        ++checked;
    }
    CHECK(checked > 200);
    MESSAGE("largest relative MSE difference: " << worst);
}

}  // namespace

TEST_CASE("aliased objective equals the direct sum after random moves: optimal filter") {
    NoiseModel gauss;
    gauss.snr_db = 30.0;
    check_random_walk(model(gauss), {WienerFilterKind::kOptimal, 0.0}, kTabulationTol);
    check_random_walk(model(dim_photons()), {WienerFilterKind::kOptimal, 0.0}, kTabulationTol);
}

TEST_CASE("aliased objective equals the direct sum after random moves: fixed NSR") {
    NoiseModel gauss;
    gauss.snr_db = 20.0;
    check_random_walk(model(gauss), {WienerFilterKind::kFixedNsr, 0.01}, kTabulationTol);
    check_random_walk(model(dim_photons()), {WienerFilterKind::kFixedNsr, 0.3}, kTabulationTol);
}

TEST_CASE("aliased objective equals the direct sum after random moves: tuned NSR") {
    NoiseModel gauss;
    gauss.snr_db = 20.0;
    check_random_walk(model(gauss), {WienerFilterKind::kTunedNsr, 0.0}, kTunedTol);
    check_random_walk(model(dim_photons()), {WienerFilterKind::kTunedNsr, 0.0}, kTunedTol);
    NoiseModel bright = dim_photons();
    bright.photons_per_pinhole = 1e5;
    check_random_walk(model(bright), {WienerFilterKind::kTunedNsr, 0.0}, kTunedTol);
}

TEST_CASE("aliased objective, noise-free model: every frequency summed exactly") {
    NoiseModel none;
    none.kind = NoiseKind::kNone;
    // Noise-free, a frequency contributes S or 0 as |P^| is exactly 0 or not: the FFT's exact
    // zeros and the incremental spectrum's 1e-16 residues differ there, so both paths read the
    // same (incremental) spectrum.
    check_random_walk(model(none), {WienerFilterKind::kOptimal, 0.0}, kExactSumTol, false);
}

TEST_CASE("MaskObjective::evaluate reads the aliased tables: same PSNR as terms()") {
    const auto m = model(dim_photons());
    const MaskObjective objective(ObjectiveWeights{}, m, {WienerFilterKind::kOptimal, 0.0});
    PatternState state(start());
    std::mt19937_64 rng(3);
    std::uniform_int_distribution<int> cell(0, kN - 1);
    for (int step = 0; step < 100; ++step) {
        const int j = std::uniform_int_distribution<int>(0, state.holes() - 1)(rng);
        const Cell to{cell(rng), cell(rng)};
        if (state.is_legal_move(j, to)) state.move(j, to);
        // PSNR error = 10 log10(1 + rel MSE error) / ... <= 4.4 kTabulationTol dB.
        CHECK(std::fabs(objective.evaluate(state) +
                        objective.terms(state).at("analytic_mmse_psnr_db")) <=
              5.0 * kTabulationTol);
    }
}

TEST_CASE("aliased model rejects a pattern size that does not divide the period") {
    NoiseModel gauss;
    CHECK_THROWS_AS(AliasedWiener(model(gauss), 7, {WienerFilterKind::kOptimal, 0.0}),
                    InvalidInput);
    const AliasedWiener fast(model(gauss), kN, {WienerFilterKind::kOptimal, 0.0});
    CHECK_THROWS_AS(fast.evaluate(ComplexPlane::Zero(4, 4)), InvalidInput);
}
