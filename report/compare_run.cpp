#include "report/compare_run.hpp"

#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "report/compare_report.hpp"
#include "report/report.hpp"

namespace pinmask {

namespace fs = std::filesystem;

namespace {

std::string fixed(double v, int digits) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v;
    return s.str();
}

// The first mask's gain over the random median on the lead figure, or that there is none.
std::string random_gain_words(const CompareOutcome& out) {
    const PairedDifference& g = *out.random_gain;
    const std::string& name = out.results.front().row.name;
    std::string s = "Gain of " + name + " over the random median on " + out.lead.name + " (" +
                    figure_words(out.lead.name) + ", " + out.lead.reason +
                    "): " + (g.difference >= 0 ? "+" : "") + fixed(g.difference, 3) +
                    " dB, standard error " + fixed(g.standard_error, 3) + " dB (the median of " +
                    std::to_string(g.samples) +
                    " random draws as an estimate of the population's; the mask's figure is "
                    "exact). ";
    if (!g.significant) {
        s += "No significant gain: the difference is under two standard errors.";
    } else if (g.difference > 0) {
        s += "A significant gain (at least two standard errors).";
    } else {
        s += "A significant LOSS: the mask is below the random median by at least two standard "
             "errors.";
    }
    return s;
}

}  // namespace

CompareRunOptions CompareRequest::run_options() const {
    CompareRunOptions r;
    MaskMetricsOptions& m = r.settings.metrics;
    m.tv = true;
    m.noise = noise;
    m.prior = prior;
    m.scenes = scene_specs_from_names(scenes);
    m.simulation.seed = seed;
    set_decoder_settings(m.simulation, wiener_nsr, tv_lambda, tv_iterations);
    if (robust) m.robust = parse_fabrication_errors(*robust);
    m.depth = depth;
    m.depth_range.from_m = depth_from_m;
    m.depth_range.to_m = depth_to_m;
    r.settings.seed = seed;
    r.baselines = baselines;
    r.baseline_count = baseline_count;
    r.validate();
    return r;
}

void CompareRequest::validate() const {
    run_options();
    if (report.empty()) return;
    report_format(report, field_ref("report"));
    const fs::path dir = fs::path(report).parent_path();
    if (!dir.empty() && !fs::is_directory(dir))
        throw invalid_field(field_ref("report"), report, "the output directory does not exist");
}

CompareReport run_compare_request(CompareRequest request, const CompareProgress& progress) {
    request.validate();
    if (request.entries.empty()) throw InvalidInput("masks: give at least one mask");
    CompareReport r;
    r.options = request.run_options();
    const Camera camera = request.entries.front().mask.camera;
    r.outcome = run_compare(std::move(request.entries), r.options, progress);
    request.entries.clear();
    // The library's words name settings by field: in the face's spelling (a given mask's source
    // is its path, left as typed).
    const auto spell = [&](const std::string& s) { return request.spell ? request.spell(s) : s; };
    CompareOutcome& out = r.outcome;
    for (CompareResult& row : out.results)
        if (row.row.kind != "input") row.row.source = spell(row.row.source);
    for (std::string& l : out.baseline_lines) l = spell(l);
    out.random_skipped = spell(out.random_skipped);
    out.mura_skipped = spell(out.mura_skipped);
    for (const std::string& w : {out.random_skipped, out.mura_skipped})
        if (!w.empty()) r.warnings.push_back(w);

    std::string& scenes = r.scenes;
    for (const std::string& s : request.scenes) scenes += (scenes.empty() ? "" : ",") + s;
    const MaskMetricsOptions& mo = r.options.settings.metrics;
    const std::string& nsr = request.wiener_nsr;
    r.settings_lines = {
        "Simulation: " + request.noise_text + ", scenes " + scenes +
        " (the first is shown on each page), Wiener NSR " + nsr + ", TV-L2 lambda " +
        request.tv_lambda + " (" + std::to_string(request.tv_iterations) +
        " iterations max), noise seed " + std::to_string(request.seed) +
        ". Analytic prior: " + mo.prior.description() + "." +
        (mo.robust.any() ? " Robust W: analytic Wiener expected under fabrication errors (" +
                               mo.robust.description() + "), decoded with the nominal PSF."
                         : "")};
    r.nsr_words = nsr == "tuned" ? "NSR tuned per mask" : "NSR " + nsr;
    r.analytic_basis = "closed form over one period, prior " + mo.prior.description() +
                       ", Wiener " + r.nsr_words + ", " + request.noise_text + " (first level)";
    r.mmse_basis = "closed form over one period, prior " + mo.prior.description() +
                   ", per-frequency optimal (MMSE) Wiener filter, " + request.noise_text +
                   " (first level)";
    if (out.random_gain) r.random_gain_text = random_gain_words(out);
    r.sim_basis = "simulated on scenes " + scenes + " (cyclic model, " + request.noise_text +
                  ", first level, noise seed " + std::to_string(request.seed) + ")";
    if (!request.report.empty()) {
        CompareSummary summary;
        summary.camera = camera;
        summary.noise_text = request.noise_text;
        summary.baseline_lines = out.baseline_lines;
        summary.settings_lines = r.settings_lines;
        summary.lead = out.lead;
        if (!r.random_gain_text.empty()) summary.baseline_lines.push_back(r.random_gain_text);
        if (!out.lead_mismatch.empty()) summary.baseline_lines.push_back(out.lead_mismatch);
        r.report_pages = render_report(compare_document(out.results, r.options.settings, summary),
                                       request.report);
    }
    r.request = std::move(request);
    return r;
}

}  // namespace pinmask
