#include "optimize/metrics/score_run.hpp"

#include <utility>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "optimize/metrics/depth_fisher.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/robust_errors.hpp"

namespace pinmask {

MaskMetricsOptions ScoreRequest::options() const {
    MaskMetricsOptions m;
    select_metrics(m, metrics);
    m.noise = noise;
    m.prior = prior;
    m.scenes = scene_specs_from_names(scenes);
    m.simulation.noise_seeds = noise_seeds;
    m.simulation.seed = seed;
    set_decoder_settings(m.simulation, wiener_nsr, tv_lambda, tv_iterations);
    if (robust) m.robust = parse_fabrication_errors(*robust);
    m.depth_range.from_m = depth_from_m;
    m.depth_range.to_m = depth_to_m;
    m.validate();
    return m;
}

namespace {

std::vector<std::string> explain_lines(const ScoreRequest& q, const MaskMetricsOptions& m) {
    std::vector<std::string> e;
    const auto line = [&](bool on, const std::string& name, const std::string& what) {
        e.push_back(name + ": " + (on ? what : "skipped (not in " + field_ref("metrics") + ")"));
    };
    line(m.sidelobes, "sidelobes", "torus autocorrelation from the n x n pattern DFT");
    line(m.spectrum, "spectrum",
         "min |P^|, flatness, open fraction, light gain from the pattern DFT; OTF condition over "
         "the kernel passband |K^| >= 0.1 max |K^|; spectral zeros |P^| < 1e-3 sqrt(K) there");
    line(m.analytic, "analytic",
         "closed-form expected Wiener MSE over one period, " + q.noise_text + ", NSR " +
             q.wiener_nsr + ", plus the per-frequency optimal Wiener bound; prior " +
             m.prior.description());
    for (const auto& [on, name] :
         {std::pair{m.wiener, std::string("wiener")}, std::pair{m.tv, std::string("tv")}}) {
        line(on, name,
             "simulated one period (cyclic model: capture = scene (*) PSF, " + q.noise_text +
                 "), " + std::to_string(m.scenes.size()) + " scene(s) x " +
                 std::to_string(q.noise_seeds) + " noise seed(s)");
    }
    if (m.robust.any()) {
        line(m.analytic, "robust",
             "the analytic figure expected under fabrication errors (" + m.robust.description() +
                 "), decoded with the nominal PSF: closed form, no sampling");
    }
    line(m.depth, "depth",
         "Cramer-Rao bound on the distance of a point source on the axis (exact-geometry PSF over "
         "the sensor, its derivative in 1/u, Poisson + read noise of the photon level), worst "
         "over " +
             std::to_string(kDepthSamples) + " distances equally spaced in 1/u");
    if (!m.tv)
        e.push_back("tv: add tv to " + field_ref("metrics") + " to run TV-L2 decodes (slow)");
    if (!(m.wiener || m.tv)) e.push_back("scene rendering: skipped (no simulated metric)");
    e.push_back("full-sensor simulation: skipped (the cyclic model needs one period only)");
    return e;
}

}  // namespace

ScoreReport run_score_request(ScoreRequest q) {
    ScoreReport r;
    r.context = std::make_shared<MetricsContext>(q.options());
    if (q.masks.empty()) throw InvalidInput("masks: give at least one mask");
    const MaskMetricsOptions& m = r.context->options();
    r.explain = explain_lines(q, m);
    for (std::size_t i = 0; i < q.masks.size(); ++i) {
        if (q.progress) q.progress(i, q.masks.size());
        ScoreRow row{q.names[i], geometry_hash(q.masks[i]),
                     compute_mask_metrics(q.masks[i], *r.context)};
        const MaskMetrics& mm = row.metrics;
        if (!mm.kernel_description.empty())
            r.explain.push_back("kernel of " + row.name + ": " + mm.kernel_description);
        if (m.analytic && q.explain) {
            const PriorRelevance pr = prior_relevance(r.context->prior(mm.period_px));
            r.explain.push_back(
                "prior at " + std::to_string(mm.period_px) +
                " px: " + std::to_string(pr.irrelevant) + " of " + std::to_string(pr.total) +
                " frequencies carry < 1e-6 of its peak power (irrelevant to the analytic error; "
                "still summed, nothing skipped); relevant up to radius " +
                std::to_string(pr.highest_relevant_radius) + " cycles per period");
        }
        r.rows.push_back(std::move(row));
    }
    q.masks.clear();
    r.request = std::move(q);
    return r;
}

}  // namespace pinmask
