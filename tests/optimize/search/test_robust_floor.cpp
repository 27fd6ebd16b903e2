// Why the nominal-PSF decoder cannot halve the fabrication loss, and what can.
//
// 1. Decomposition (closed form, optimize/metrics/robust_wiener): under +-10 % side and 2 um jitter
// the
//    loss of the tuned fixed-NSR Wiener is almost all size bias; masks of every K, MURA and the
//    searched ones are listed with -s. The size bias is common to every pinhole, so per frequency
//    the fabricated transfer is P^ kappa_s J / K: the pattern cancels from the mismatch
//    kappa_s / kappa, and min_u E|u T - 1|^2 S = S (1 - |E kappa_s|^2 / E|kappa_s|^2) bounds the
//    fabricated error of ANY pattern with ANY linear decoder (pattern_independent_floor_mse).
//    Checked: every mask and decoder stays above that floor, and the robust filter (the
//    per-frequency minimiser of the expected fabricated error) is at least as good as every
//    other decoder on the fabricated masks.
// 2. With the decoder `pinmask decode` applies (nominal PSF, fixed NSR tuned for the mask), a
//    search minimising the loss itself among masks whose fabricated PSNR is at least the nominal
//    design's stays above half the nominal design's loss: what a pattern can do alone.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <random>
#include <sstream>

#include "design/optics/camera.hpp"
#include "design/pattern/mura.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/nsr_tuning.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/search/pattern_state.hpp"
#include "optimize/search/search.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "tests/optimize/search/robust_setup.hpp"
#include "tests/research/expected_psf_decoder.hpp"

namespace pinmask {
namespace {

Mask camera_mask(const Pattern& p) {
    Mask m;
    m.camera = paper_camera();
    m.pattern = p;
    m.psf.pixels_per_cell = 8;
    m.psf.kernel.model = "box";
    return m;
}

NoiseModel noise50() {
    NoiseModel nm;
    nm.snr_db = 50.0;
    return nm;
}

ScenePrior prior_for(int m) {
    PriorSpec ps;
    ps.count = 8;
    return make_scene_prior(ps, m);
}

using test::ten_percent_errors;

// The pattern of `search` (nominal objective) on the test camera, as in test_robust_search.
Mask nominal_search_mask() {
    return run_search_pipeline(test::robust_camera_options()).ranked.front().mask;
}

class FunctionObjective : public SearchObjective {
  public:
    explicit FunctionObjective(std::function<double(const ComplexPlane&)> f) : f_(std::move(f)) {}
    double evaluate(const PatternState& s) const override { return f_(s.spectrum()); }
    std::map<std::string, double> terms(const PatternState& s) const override {
        return {{"objective", evaluate(s)}};
    }

  private:
    std::function<double(const ComplexPlane&)> f_;
};

std::string fixed(double v) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(2);
    s << v;
    return s.str();
}

}  // namespace

TEST_CASE("robust loss decomposition: size bias dominates; no decoder beats the floor") {
    constexpr double kRelTolerance = 1e-9;  // rounding of sums over 128^2 frequencies
    const FabricationErrors e = ten_percent_errors();
    std::vector<std::pair<std::string, Mask>> masks{{"search", nominal_search_mask()}};
    for (int k : {5, 10, 20, 30, 40, 50}) {
        for (unsigned seed = 1; seed <= 3; ++seed) {
            RandomSparseOptions r;
            r.n = 16;
            r.holes = k;
            std::mt19937_64 rng(seed);
            masks.push_back({"random seed " + std::to_string(seed),
                             camera_mask(random_sparse_pattern(r, rng))});
        }
    }
    masks.push_back({"MURA 13", camera_mask(mura_pattern(13, 0.0))});
    masks.push_back({"MURA 17", camera_mask(mura_pattern(17, 0.0))});
    FabricationErrors size_only = e, jitter_only = e;
    size_only.jitter_m = 0.0;
    jitter_only.size_bias_m = 0.0;
    MESSAGE(
        "mask: tuned-NSR nominal / fabricated / loss (size alone, jitter alone) | expected-PSF "
        "decoder | nominal optimal filter | robust filter | floor (dB)");
    for (const auto& entry : masks) {
        const std::string name = entry.first;
        const Mask& mask = entry.second;
        const int m = mask.pattern.n * mask.psf.pixels_per_cell;
        const ScenePrior prior = prior_for(m);
        const RobustWienerModel all(mask, e, prior, noise50());
        const RobustWienerModel s_only(mask, size_only, prior, noise50());
        const RobustWienerModel j_only(mask, jitter_only, prior, noise50());
        const ComplexPlane p = pattern_spectrum(mask.pattern);
        const RobustError tuned = all.evaluate_tuned_nsr(p);
        const RobustError expected = evaluate_expected_psf_tuned_nsr(all, p);
        const RobustError optimal = all.evaluate(p, {WienerFilterKind::kOptimal, 0.0});
        const RobustError robust = all.evaluate_robust_filter(p);
        const double floor = all.pattern_independent_floor_mse();
        const double size_loss = s_only.evaluate_tuned_nsr(p).loss_db();
        const double jitter_loss = j_only.evaluate_tuned_nsr(p).loss_db();
        MESSAGE(name << " K=" << mask.pattern.pinholes.size() << ": "
                     << fixed(tuned.nominal.psnr_db) << " / " << fixed(tuned.psnr_db) << " / "
                     << fixed(tuned.loss_db()) << " (" << fixed(size_loss) << ", "
                     << fixed(jitter_loss) << ") | " << fixed(expected.nominal.psnr_db) << " / "
                     << fixed(expected.psnr_db) << " | " << fixed(optimal.nominal.psnr_db) << " / "
                     << fixed(optimal.psnr_db) << " | " << fixed(robust.nominal.psnr_db) << " / "
                     << fixed(robust.psnr_db) << " | " << fixed(psnr_from_mse(floor)));
        CAPTURE(name);
        // The size bias carries the loss; jitter of 2 um (0.036 px) adds little.
        CHECK(size_loss >= 0.9 * tuned.loss_db());
        CHECK(jitter_loss <= 0.1 * tuned.loss_db());
        // The floor bounds every decoder; the robust filter is the best on fabricated masks.
        for (const RobustError* r : {&tuned, &expected, &optimal, &robust}) {
            CHECK(r->mse >= floor * (1.0 - kRelTolerance));
            CHECK(robust.mse <= r->mse * (1.0 + kRelTolerance));
        }
        for (const double nsr : {1e-5, 1e-4, 1e-3, 1e-2}) {
            const RobustError f = all.evaluate(p, {WienerFilterKind::kFixedNsr, nsr});
            CHECK(robust.mse <= f.mse * (1.0 + kRelTolerance));
            const RobustError fx =
                evaluate_expected_psf(all, p, {WienerFilterKind::kFixedNsr, nsr});
            CHECK(robust.mse <= fx.mse * (1.0 + kRelTolerance));
        }
    }
}

TEST_CASE("a scalar NSR tuned for the fabricated masks does not halve the loss either") {
    // The decoders `pinmask decode` can run (a PSF and one NSR): the nominal or the expected
    // fabricated PSF, with the NSR tuned for the fabricated masks instead of the nominal one.
    constexpr double kLossRatioBar = 0.5;   // measured 0.80 (nominal PSF), 0.74 (expected PSF)
    constexpr double kRelTolerance = 1e-3;  // golden-section resolution of the tuned NSR
    const Mask mask = nominal_search_mask();
    const RobustWienerModel model(mask, ten_percent_errors(), prior_for(128), noise50());
    const ComplexPlane p = pattern_spectrum(mask.pattern);
    const RobustError baseline = model.evaluate_tuned_nsr(p);
    const RobustError robust = model.evaluate_robust_filter(p);
    for (const bool expected_psf : {false, true}) {
        const std::string name = expected_psf ? "expected" : "nominal";
        const auto evaluate = [&](double nsr) {
            const WienerFilterSpec f{WienerFilterKind::kFixedNsr, nsr};
            return expected_psf ? evaluate_expected_psf(model, p, f) : model.evaluate(p, f);
        };
        const double nsr = tune_log_weight([&](double w) { return evaluate(w).mse; }).x;
        const RobustError r = evaluate(nsr);
        const RobustError t =
            expected_psf ? evaluate_expected_psf_tuned_nsr(model, p) : model.evaluate_tuned_nsr(p);
        MESSAGE(name << " PSF, NSR " << nsr << " tuned for the fabricated masks: "
                     << fixed(r.nominal.psnr_db) << " / " << fixed(r.psnr_db) << " dB, loss "
                     << r.loss_db() << " dB, ratio to the tuned-NSR nominal decoder "
                     << r.loss_db() / baseline.loss_db());
        CAPTURE(name);
        CHECK(r.mse <= t.mse * (1.0 + kRelTolerance));  // it is tuned for this
        CHECK(robust.mse <= r.mse);                     // the robust filter is better still
        CHECK(r.loss_db() > kLossRatioBar * baseline.loss_db());
    }
}

TEST_CASE("with the nominal-PSF decoder no pattern halves the loss at equal fabricated PSNR") {
    constexpr double kLossRatioBar = 0.5;  // the required ratio; measured 0.79 and 0.61 (analytic)
    constexpr double kPenaltyPerDb = 10.0;
    const FabricationErrors e = ten_percent_errors();
    const Mask nominal = nominal_search_mask();
    const auto model = std::make_shared<RobustWienerModel>(nominal, e, prior_for(128), noise50());
    const RobustError ref = model->evaluate_tuned_nsr(pattern_spectrum(nominal.pattern));
    MESSAGE("nominal design (tuned NSR): " << ref.nominal.psnr_db << " / " << ref.psnr_db
                                           << " dB, loss " << ref.loss_db() << " dB");
    // Minimise the loss itself, K in 5..50; constraint (penalised per dB): the fabricated PSNR
    // at least the nominal design's, or (the brief's looser one) the nominal PSNR within 1 dB.
    for (const bool equal_fabricated : {true, false}) {
        const auto penalty = [&](const RobustError& r) {
            return kPenaltyPerDb * (equal_fabricated ? std::max(0.0, ref.psnr_db - r.psnr_db)
                                                     : std::max(0.0, ref.nominal.psnr_db - 1.0 -
                                                                         r.nominal.psnr_db));
        };
        const FunctionObjective objective([&](const ComplexPlane& p) {
            const RobustError r = model->evaluate_tuned_nsr(p);
            return r.loss_db() + penalty(r);
        });
        SearchOptions so;
        so.threads = 1;
        so.time_budget_s = 0.0;
        so.max_evaluations = 2000;
        so.anneal_restart_moves = 1000;
        so.seed = 3;
        so.top = 1;
        so.min_holes = 5;
        so.max_holes = 50;
        const auto sample = [](std::mt19937_64& rng) {
            RandomSparseOptions r;
            r.n = 16;
            r.holes = std::uniform_int_distribution<int>(5, 40)(rng);
            return random_sparse_pattern(r, rng);
        };
        const SearchSummary s = run_search(objective, so, sample);
        REQUIRE(!s.ranked.empty());
        const Pattern& best_pattern = s.ranked.front().pattern;
        const RobustError best = model->evaluate_tuned_nsr(pattern_spectrum(best_pattern));
        MESSAGE("loss-minimising search ("
                << std::string(equal_fabricated ? "fabricated >= nominal design's"
                                                : "nominal within 1 dB")
                << "), K=" << best_pattern.pinholes.size() << ": " << best.nominal.psnr_db << " / "
                << best.psnr_db << " dB, loss " << best.loss_db() << " dB, ratio "
                << best.loss_db() / ref.loss_db());
        // The search did its job: at least as good as the nominal design under its objective.
        CHECK(best.loss_db() + penalty(best) <= ref.loss_db());
        CHECK(penalty(best) <= 0.01 * kPenaltyPerDb);  // the constraint holds within 0.01 dB
        CHECK(best.loss_db() > kLossRatioBar * ref.loss_db());
    }
}

}  // namespace pinmask
