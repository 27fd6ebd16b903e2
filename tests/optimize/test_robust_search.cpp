// Must-show of issue 13 point 6, measured: under +-10 % pinhole size error and 2 um position
// jitter, how much simulated PSNR (natural scenes the search never saw, fixed-seed fabricated
// PSFs) the robust design loses against the nominal design.
//
// Both designs are a pattern AND its decoder, each optimised for its own objective, with the same
// decoder class (a per-frequency linear filter, which `search` optimises by default through the
// analytic optimal-Wiener figure):
//   nominal design  the mask of `search` (nominal objective), decoded by the per-frequency
//                   optimal Wiener filter of its nominal PSF (the filter that objective scores);
//   robust design   the mask of a search whose objective is the expected fabricated PSNR of the
//                   decoder chosen for the errors (RobustObjectiveDecoder::kRobustFilter: per
//                   frequency the filter minimising the expected fabricated error), decoded by
//                   that filter.
// The bar: the robust design loses at most kLossRatioBar of what the nominal design loses, and it
// is not bought with nominal quality: its fabricated PSNR is at least the nominal design's (the
// nominal PSNR it gives up is less than the loss it saves). A third figure, the nominal mask with
// the tuned fixed-NSR Wiener (the decoder `pinmask decode` applies today), is reported and the
// robust design must beat it both nominally and fabricated.
//
// What does not reach the bar (test_robust_floor, README "Measured figures"): any search with the
// nominal-PSF decoder (ratio 0.94 for `search --objective robust`; the loss-minimising search
// 0.82 at equal fabricated PSNR), because the loss is the decoder's kernel mismatch.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "design/camera.hpp"
#include "design/psf.hpp"
#include "design/random_sparse.hpp"
#include "optimize/mask_metrics.hpp"
#include "optimize/robust_sample.hpp"
#include "optimize/robust_wiener.hpp"
#include "optimize/scenes.hpp"
#include "optimize/search.hpp"
#include "optimize/search_pipeline.hpp"

namespace pinmask {
namespace {

SearchPipelineOptions camera_options() {
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
    o.noise.snr_db = 50.0;  // the error is visible above the noise
    o.prior.count = 8;
    return o;
}

std::vector<NamedScene> held_out_scenes(int m) {
    // Held-out natural textures: the prior uses seeds 1000..1007, the scored scene seed 0.
    std::vector<NamedScene> scenes;
    for (std::uint64_t seed : {7001, 7002, 7003, 7004}) {
        SceneSpec s;
        s.kind = SceneKind::kNatural;
        s.seed = seed;
        scenes.push_back({"natural-" + std::to_string(seed), make_scene(s, m, m)});
    }
    return scenes;
}

FabricationErrors ten_percent_errors() {
    FabricationErrors e;
    e.size_bias_m = 44e-6;  // 10 % of the paper's 440 um pinhole side
    e.jitter_m = 2e-6;
    return e;
}

}  // namespace

TEST_CASE("robust design (pattern and decoder) under +-10 % size and 2 um jitter: half the loss") {
    constexpr double kLossRatioBar = 0.5;             // the bar; measured 0.37
    constexpr double kPredictedLossTolerance = 0.25;  // relative, closed form vs simulation
    constexpr int kDraws = 16;                        // fabricated PSFs per mask
    const FabricationErrors e = ten_percent_errors();
    const int m = 128;
    const std::vector<NamedScene> scenes = held_out_scenes(m);
    SearchPipelineOptions o = camera_options();
    o.robust = e;  // reports the robust figure beside the nominal objective
    const ScenePrior prior = make_scene_prior(o.prior, m);

    // Nominal design: `search`'s mask with the filter its objective scores.
    const SearchPipelineSummary nominal_search = run_search_pipeline(o);
    REQUIRE(!nominal_search.ranked.empty());
    const Mask nominal_mask = nominal_search.ranked.front().mask;
    const RobustWienerModel nominal_model(nominal_mask, e, prior, o.noise);
    const ComplexPlane pn = pattern_spectrum(nominal_mask.pattern);
    const FabricatedQuality qn = fabricated_filter_quality(
        nominal_mask, e, scenes, o.noise,
        nominal_model.filter_response(pn, {WienerFilterKind::kOptimal, 0.0}), kDraws, 11);
    const RobustError an = nominal_model.evaluate(pn, {WienerFilterKind::kOptimal, 0.0});

    // Robust design: the search over the same patterns with the robust filter's figure.
    const Mask tmpl = o.tmpl;
    const auto model = std::make_shared<RobustWienerModel>(tmpl, e, prior, o.noise);
    const RobustObjective objective(ObjectiveWeights{}, model, {WienerFilterKind::kOptimal, 0.0},
                                    RobustObjectiveDecoder::kRobustFilter);
    const auto sample = [&](std::mt19937_64& rng) {
        RandomSparseOptions r;
        r.n = o.tmpl.pattern.n;
        r.holes = o.holes;
        r.min_spacing_cells = o.tmpl.pattern.min_spacing_cells;
        return random_sparse_pattern(r, rng);
    };
    const SearchSummary robust_search = run_search(objective, o.search, sample);
    REQUIRE(!robust_search.ranked.empty());
    Mask robust_mask = tmpl;
    robust_mask.pattern = robust_search.ranked.front().pattern;
    const ComplexPlane pr = pattern_spectrum(robust_mask.pattern);
    const FabricatedQuality qr = fabricated_filter_quality(
        robust_mask, e, scenes, o.noise, model->robust_filter_response(pr), kDraws, 11);
    const RobustError ar = model->evaluate_robust_filter(pr);

    // Today's decoder on the nominal mask: fixed NSR tuned for the nominal mask.
    const RobustError at = nominal_model.evaluate_tuned_nsr(pn);
    const FabricatedQuality qt =
        fabricated_wiener_quality(nominal_mask, e, scenes, o.noise, at.nominal.nsr, kDraws, 11);

    // `search --objective robust` (nominal-PSF decoder): the mask decoded with the tuned NSR.
    SearchPipelineOptions ro = o;
    ro.objective = ObjectiveKind::kRobust;
    const SearchPipelineSummary robust_objective = run_search_pipeline(ro);
    REQUIRE(!robust_objective.ranked.empty());
    const Mask& ro_mask = robust_objective.ranked.front().mask;
    const RobustWienerModel ro_model(ro_mask, e, prior, o.noise);
    const RobustError ao = ro_model.evaluate_tuned_nsr(pattern_spectrum(ro_mask.pattern));
    const FabricatedQuality qo =
        fabricated_wiener_quality(ro_mask, e, scenes, o.noise, ao.nominal.nsr, kDraws, 11);
    const double loss_o = qo.nominal_psnr_db - qo.fabricated_psnr_db;

    // The nominal mask decoded with the expected fabricated PSF (NSR tuned for it).
    const RobustError ax = nominal_model.evaluate_tuned_nsr(pn, RobustDecoderPsf::kExpectedPsf);
    const FabricatedQuality qx = fabricated_filter_quality(
        nominal_mask, e, scenes, o.noise,
        nominal_model.filter_response(pn, {WienerFilterKind::kTunedNsr, 0.0},
                                      RobustDecoderPsf::kExpectedPsf),
        kDraws, 11);
    const double loss_x = qx.nominal_psnr_db - qx.fabricated_psnr_db;

    const double loss_n = qn.nominal_psnr_db - qn.fabricated_psnr_db;
    const double loss_r = qr.nominal_psnr_db - qr.fabricated_psnr_db;
    const double loss_t = qt.nominal_psnr_db - qt.fabricated_psnr_db;
    MESSAGE("nominal design (optimal filter): "
            << qn.nominal_psnr_db << " dB nominal, " << qn.fabricated_psnr_db
            << " dB fabricated, loss " << loss_n << " dB (predicted " << an.loss_db() << ")");
    MESSAGE("robust design (robust filter): "
            << qr.nominal_psnr_db << " dB nominal, " << qr.fabricated_psnr_db
            << " dB fabricated, loss " << loss_r << " dB (predicted " << ar.loss_db() << ")");
    MESSAGE("nominal mask, tuned fixed NSR: "
            << qt.nominal_psnr_db << " dB nominal, " << qt.fabricated_psnr_db
            << " dB fabricated, loss " << loss_t << " dB (predicted " << at.loss_db() << ")");
    MESSAGE("search --objective robust mask, tuned fixed NSR: "
            << qo.nominal_psnr_db << " dB nominal, " << qo.fabricated_psnr_db
            << " dB fabricated, loss " << loss_o << " dB (predicted " << ao.loss_db()
            << "); ratio to the line above " << loss_o / loss_t);
    MESSAGE("nominal mask, expected fabricated PSF, tuned NSR: "
            << qx.nominal_psnr_db << " dB nominal, " << qx.fabricated_psnr_db
            << " dB fabricated, loss " << loss_x << " dB (predicted " << ax.loss_db()
            << "); ratio to the tuned-NSR line " << loss_x / loss_t);
    MESSAGE("robust / nominal loss " << loss_r / loss_n << "; against the tuned-NSR decoder "
                                     << loss_r / loss_t);
    REQUIRE(loss_n > 0.0);
    CHECK(loss_r <= kLossRatioBar * loss_n);
    // Not bought with nominal quality: nominal PSNR given up < loss saved.
    CHECK(qn.nominal_psnr_db - qr.nominal_psnr_db < loss_n - loss_r);
    CHECK(qr.fabricated_psnr_db > qn.fabricated_psnr_db);
    // Better than today's decoder on the nominal mask, nominally and fabricated.
    CHECK(qr.nominal_psnr_db > qt.nominal_psnr_db);
    CHECK(qr.fabricated_psnr_db > qt.fabricated_psnr_db);
    // The closed form predicts the simulated losses.
    CHECK(std::abs(an.loss_db() - loss_n) <= kPredictedLossTolerance * loss_n);
    CHECK(std::abs(ar.loss_db() - loss_r) <= kPredictedLossTolerance * loss_r);
    CHECK(std::abs(at.loss_db() - loss_t) <= kPredictedLossTolerance * loss_t);
    CHECK(std::abs(ao.loss_db() - loss_o) <= kPredictedLossTolerance * loss_o);
    CHECK(std::abs(ax.loss_db() - loss_x) <= kPredictedLossTolerance * loss_x);
    // The nominal-PSF robust objective finds a mask at least as good under that objective.
    CHECK(robust_objective.ranked.front().mask.provenance.scores.at("robust_wiener_psnr_db") >=
          nominal_search.ranked.front().mask.provenance.scores.at("robust_wiener_psnr_db"));
}

}  // namespace pinmask
