// The robust-design requirement, measured: under +-10 % pinhole size error and 2 um position
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
// What does not reach the bar (test_robust_floor, docs/benchmarks.md): any search with the
// nominal-PSF decoder (ratio 0.94 for `search --objective robust`; the loss-minimising search
// 0.82 at equal fabricated PSNR), because the loss is the decoder's kernel mismatch.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "design/optics/camera.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/search/robust_objective.hpp"
#include "optimize/search/search.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "optimize/simulate/scenes.hpp"
#include "tests/optimize/search/robust_setup.hpp"
#include "tests/research/expected_psf_decoder.hpp"
#include "tests/research/fabricated_sample.hpp"

namespace pinmask {
namespace {

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

// The bar: the robust design loses at most this fraction of the nominal design's loss.
constexpr double kLossRatioBar = 0.5;

// The figures of one robust-design measurement (search seed `seed`), simulated (q*) and closed
// form (a*): the nominal design (n), the robust design (r), the nominal mask with the tuned fixed
// NSR (t), `search --objective robust`'s mask with it (o), the nominal mask decoded with the
// expected fabricated PSF (x); the analytic_robust_mmse_psnr_db scores of the two pipeline
// searches.
struct RobustDesignFigures {
    FabricatedQuality qn, qr, qt, qo, qx;
    RobustError an, ar, at, ao, ax;
    double nominal_search_score = 0.0, robust_objective_score = 0.0;
    double loss(const FabricatedQuality& q) const {
        return q.nominal_psnr_db - q.fabricated_psnr_db;
    }
};

RobustDesignFigures measure_robust_design(std::uint64_t seed) {
    constexpr int kDraws = 16;  // fabricated PSFs per mask
    const FabricationErrors e = test::ten_percent_errors();
    const int m = 128;
    const std::vector<NamedScene> scenes = held_out_scenes(m);
    SearchPipelineOptions o = test::robust_camera_options();
    o.search.seed = seed;
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
    const RobustError ax = evaluate_expected_psf_tuned_nsr(nominal_model, pn);
    const FabricatedQuality qx = fabricated_filter_quality(
        nominal_mask, e, scenes, o.noise,
        expected_psf_filter_response(nominal_model, pn, {WienerFilterKind::kTunedNsr, 0.0}), kDraws,
        11);
    const double loss_x = qx.nominal_psnr_db - qx.fabricated_psnr_db;

    RobustDesignFigures f{qn, qr, qt, qo, qx, an, ar, at, ao, ax};
    f.nominal_search_score =
        nominal_search.ranked.front().mask.provenance.scores.at("analytic_robust_mmse_psnr_db");
    f.robust_objective_score =
        robust_objective.ranked.front().mask.provenance.scores.at("analytic_robust_mmse_psnr_db");
    const double loss_n = f.loss(qn), loss_r = f.loss(qr), loss_t = f.loss(qt);
    MESSAGE("search seed " << seed);
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
    return f;
}

// The bar on one measurement: the robust design loses at most kLossRatioBar of the nominal
// design's loss, and not by giving up nominal quality.
void check_half_the_loss(const RobustDesignFigures& f) {
    const double loss_n = f.loss(f.qn), loss_r = f.loss(f.qr);
    REQUIRE(loss_n > 0.0);
    CHECK(loss_r <= kLossRatioBar * loss_n);
    // Not bought with nominal quality: nominal PSNR given up < loss saved.
    CHECK(f.qn.nominal_psnr_db - f.qr.nominal_psnr_db < loss_n - loss_r);
    CHECK(f.qr.fabricated_psnr_db > f.qn.fabricated_psnr_db);
}

}  // namespace

TEST_CASE("robust design (pattern and decoder) under +-10 % size and 2 um jitter: half the loss") {
    // Search seed 3: measured loss ratio 0.37 (docs/benchmarks.md, "Fabrication robustness").
    constexpr double kPredictedLossTolerance = 0.25;  // relative, closed form vs simulation
    const RobustDesignFigures f = measure_robust_design(3);
    const FabricatedQuality &qn = f.qn, &qr = f.qr, &qt = f.qt, &qo = f.qo, &qx = f.qx;
    const RobustError &an = f.an, &ar = f.ar, &at = f.at, &ao = f.ao, &ax = f.ax;
    const double loss_n = f.loss(qn), loss_r = f.loss(qr), loss_t = f.loss(qt);
    const double loss_o = f.loss(qo), loss_x = f.loss(qx);
    check_half_the_loss(f);
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
    CHECK(f.robust_objective_score >= f.nominal_search_score);
}

// Slow (CTest slow-robust-design-seeds, label slow; minutes): the bar over search seeds 3, 5
// and 7. Reproduces docs/benchmarks.md "Fabrication robustness": loss ratios 0.37, 0.37 and 0.36,
// so each seed holds the 0.5 bar with a margin of at least 0.13 (plus the fabricated PSNR gain
// and the nominal PSNR given up below the loss saved).
TEST_CASE("robust design over search seeds 3 5 7: half the loss on every seed" * doctest::skip()) {
    for (const std::uint64_t seed : {3, 5, 7}) {
        CAPTURE(seed);
        check_half_the_loss(measure_robust_design(seed));
    }
}

}  // namespace pinmask
