#include "optimize/metrics/compare.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "core/version.hpp"
#include "decode/capture/decoder.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/mura.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/kernel_model.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/autocorrelation.hpp"
#include "optimize/metrics/figure_names.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/paired_difference.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/simulate.hpp"

namespace pinmask {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
// A file's recorded figure and compare's own agree to this (relative): the same closed form on
// the same inputs, summed in the same order.
constexpr double kSameFigureTolerance = 1e-9;

// Zero frequency / zero shift moved from (0, 0) to (rows / 2, cols / 2).
Plane centred(const Plane& p) {
    return circshift(p, static_cast<int>(p.rows() / 2), static_cast<int>(p.cols() / 2));
}

Plane channel_mean(const Image& img) {
    Plane out = Plane::Zero(img.rows(), img.cols());
    for (const Plane& ch : img.channels) out += ch;
    return out / static_cast<double>(img.n_channels());
}

std::string kernel_text(const Kernel& k) {
    std::ostringstream s;
    s << kernel_model_name(k.model) << " (" << k.model_reason << "), " << k.values.rows() << " x "
      << k.values.cols() << " px";
    return s.str();
}

void fill_pictures(CompareResult& r, const Mask& mask, const Plane& psf, const ComplexPlane& otf,
                   const std::vector<int>& autocorrelation, const NamedScene& shown,
                   const CompareSettings& s) {
    ComparePictures& p = r.pictures;
    const int n = mask.pattern.n, m = static_cast<int>(psf.rows());
    p.pattern = Plane::Zero(n, n);
    for (const Cell& c : mask.pattern.pinholes) p.pattern(c.row, c.col) = 1.0;
    p.psf = psf;
    const double dc = std::abs(otf(0, 0));
    p.log_otf = centred(otf.abs().unaryExpr([dc](double a) { return std::log10(a / dc); }));
    Plane ac(n, n);
    for (int i = 0; i < n * n; ++i) ac(i / n, i % n) = autocorrelation[static_cast<std::size_t>(i)];
    p.autocorrelation = centred(ac);

    // One capture of the shown scene, decoded with the weights the table's figures used.
    SimulationOptions so;
    so.noise = s.metrics.noise.front().model;
    so.seed = s.metrics.simulation.seed;
    const int holes = static_cast<int>(mask.pattern.pinholes.size());
    const SimulatedCapture cap = simulate_capture(shown.image, psf, holes, n * n, so);
    Image wiener, tv;
    for (const Plane& ch : cap.capture.channels) {
        DecodeOptions w;
        w.method = DecodeMethod::kWiener;
        w.wiener.nsr = r.row.sim_wiener_nsr;
        wiener.channels.push_back(decode_plane(ch, psf, w).image);
        DecodeOptions t;
        t.method = DecodeMethod::kTv;
        t.tv.lambda = r.row.sim_tv_lambda;
        t.iterative.max_iterations = s.metrics.simulation.tv_iterations;
        t.iterative.tolerance = s.metrics.simulation.tv_tolerance;
        t.iterative.record_history = false;
        const DecodeResult d = decode_plane(ch, psf, t);
        p.tv_iterations = std::max(p.tv_iterations, d.iterations);
        tv.channels.push_back(d.image);
    }
    p.scene_name = shown.name;
    p.scene = channel_mean(shown.image);
    p.capture = channel_mean(cap.capture);
    p.wiener = channel_mean(wiener);
    p.tv = channel_mean(tv);
    const Plane& clean = cap.clean.channels[0];
    p.capture_sigma = std::sqrt(mean_noise_variance(
        so.noise, {clean.mean(), clean.square().mean(), holes, n * n}));  // as add_noise draws it
    const bool has_ssim = m >= kSsimWindow;
    p.wiener_psnr_db = psnr_db(wiener, shown.image);
    p.tv_psnr_db = psnr_db(tv, shown.image);
    p.wiener_ssim = has_ssim ? ssim(wiener, shown.image) : kNan;
    p.tv_ssim = has_ssim ? ssim(tv, shown.image) : kNan;
}

// Each row's difference to the first: the lead figure exactly, the simulated ones paired over
// the first level's scenes; and the first mask's gain over the random median.
void add_differences(CompareOutcome& out) {
    const CompareRow& a = out.results.front().row;
    const auto scenes = [](const std::optional<SimulatedQuality>& q) {
        std::vector<double> v;
        for (const SceneQuality& s : q->scenes) v.push_back(s.psnr_db);
        return v;
    };
    const LevelMetrics& la = a.metrics.levels.front();
    for (std::size_t i = 1; i < out.results.size(); ++i) {
        CompareRow& b = out.results[i].row;
        const LevelMetrics& lb = b.metrics.levels.front();
        b.to_first = {
            {out.lead.name,
             exact_difference(row_figure(b, out.lead.name), row_figure(a, out.lead.name))},
            {"sim_wiener_psnr_db", paired_difference(scenes(lb.wiener), scenes(la.wiener))},
            {"sim_tv_psnr_db", paired_difference(scenes(lb.tv), scenes(la.tv))}};
    }
    if (!out.random) return;
    PairedDifference g;
    g.difference = row_figure(a, out.lead.name) - out.random->median_psnr_db;
    g.standard_error = out.random->median_standard_error_db;
    g.samples = out.random->count;
    g.significant = std::isfinite(g.standard_error) &&
                    std::abs(g.difference) >= kSignificantStandardErrors * g.standard_error &&
                    g.difference != 0.0;
    out.random_gain = g;
}

}  // namespace

void validate(const CompareSettings& s) {
    s.metrics.validate();
    if (!(s.metrics.sidelobes && s.metrics.spectrum && s.metrics.analytic && s.metrics.wiener &&
          s.metrics.tv)) {
        throw InvalidInput(
            "compare settings: every metric (sidelobes, spectrum, analytic, "
            "wiener, tv) must be on");
    }
}

CompareResult compare_mask(const CompareEntry& e, const CompareSettings& s,
                           MetricsContext& context) {
    const Mask& mask = e.mask;
    const int n = mask.pattern.n, ppc = mask.psf.pixels_per_cell, m = n * ppc;
    check_psf_memory(n, ppc, 12, 4);  // PSF, pictures, scene planes; kernel, OTF, decoder spectra
    CompareResult r;
    CompareRow& row = r.row;
    row.name = e.name;
    row.kind = e.kind;
    row.source = e.source;
    row.geometry_hash = geometry_hash(mask);
    row.n = n;
    row.holes = static_cast<int>(mask.pattern.pinholes.size());
    row.pixels_per_cell = ppc;
    row.period_px = m;
    row.min_spacing_cells = mask.pattern.min_spacing_cells;
    row.spacing_violations = static_cast<long long>(spacing_violations(mask.pattern).size());
    row.spacing_ok = row.spacing_violations == 0;

    row.metrics = compute_mask_metrics(mask, context);
    const MaskMetrics& mm = row.metrics;
    row.max_sidelobe = mm.sidelobes->max_sidelobe;
    row.peak_to_sidelobe_ratio = mm.sidelobes->peak_to_sidelobe_ratio;
    row.min_abs_pattern_spectrum = mm.spectrum->min_abs_pattern_spectrum;
    row.spectral_flatness = mm.spectrum->spectral_flatness;
    row.otf_condition_number = mm.otf->condition_number;
    const LevelMetrics& first = mm.levels.front();
    row.analytic_wiener_psnr_db = first.analytic->psnr_db;
    row.analytic_wiener_nsr = first.analytic->nsr;
    row.analytic_mmse_psnr_db = first.analytic->mmse_psnr_db;
    if (first.robust) row.analytic_robust_wiener_psnr_db = first.robust->psnr_db;
    row.sim_wiener_psnr_db = first.wiener->mean_psnr_db;
    row.sim_wiener_ssim = first.wiener->mean_ssim;
    row.sim_wiener_nsr = first.wiener->weight;
    row.sim_tv_psnr_db = first.tv->mean_psnr_db;
    row.sim_tv_ssim = first.tv->mean_ssim;
    row.sim_tv_lambda = first.tv->weight;

    const Kernel kernel = mask_kernel(mask);
    r.pictures.kernel = kernel_text(kernel);
    const ComplexPlane spectrum = pattern_spectrum(mask.pattern);
    const std::vector<int> ac = autocorrelation_from_spectrum(spectrum);
    const ComplexPlane kernel_half = kernel_spectrum(kernel, n, ppc);
    const Plane psf = synthesize_psf(mask.pattern, kernel, ppc);
    // The OTF from the spectra above (psf_otf would recompute both).
    const ComplexPlane otf =
        expand_half_spectrum(combine_spectra(spectrum, kernel_half, row.holes), m);
    fill_pictures(r, mask, psf, otf, ac, context.scenes(m).front(), s);
    return r;
}

double row_figure(const CompareRow& r, const std::string& name) {
    if (name == "analytic_mmse_psnr_db") return r.analytic_mmse_psnr_db;
    if (name == "analytic_wiener_psnr_db") return r.analytic_wiener_psnr_db;
    if (name == "sim_wiener_psnr_db") return r.sim_wiener_psnr_db;
    if (name == "sim_tv_psnr_db") return r.sim_tv_psnr_db;
    return kNan;
}

LeadFigure compare_lead_figure(const Mask& first, const NoiseModel& noise) {
    const std::string& f = first.provenance.objective_figure;
    if (f == "analytic_mmse_psnr_db" || f == "analytic_wiener_psnr_db")
        return {f, "the figure the first mask's search optimised"};
    if (f == "analytic_robust_mmse_psnr_db" || f == "analytic_robust_wiener_psnr_db") {
        const std::string nominal = f == "analytic_robust_mmse_psnr_db" ? "analytic_mmse_psnr_db"
                                                                        : "analytic_wiener_psnr_db";
        return {nominal,
                "the nominal figure of the filter the first mask's search optimised under "
                "fabrication errors (" +
                    f + ")"};
    }
    const std::string fallback =
        parse_search_filter("auto", noise).kind == WienerFilterKind::kOptimal
            ? "analytic_mmse_psnr_db"
            : "analytic_wiener_psnr_db";
    return {fallback, f.empty() ? "the figure search optimises by default at this noise (the first "
                                  "mask records no search's figure)"
                                : "the figure search optimises by default at this noise (the "
                                  "first mask's search optimised " +
                                      f + ")"};
}

RandomMedian random_median_baseline(const Mask& tmpl, int count, const CompareSettings& s,
                                    MetricsContext& context, const std::string& figure,
                                    const std::function<void(int, int)>& progress) {
    if (figure != "analytic_mmse_psnr_db" && figure != "analytic_wiener_psnr_db")
        throw InvalidInput("random baseline: cannot rank by '" + figure + "'");
    if (count < 1 || count > kMaxBaselineCount) {
        throw invalid_field(field_ref("baseline_count"), std::to_string(count),
                            "must be between 1 and 10000 (random draws; the median settles long "
                            "before)");
    }
    RandomSparseOptions ro;
    ro.n = tmpl.pattern.n;
    ro.holes = static_cast<int>(tmpl.pattern.pinholes.size());
    ro.min_spacing_cells = tmpl.pattern.min_spacing_cells;
    ro.tiles_rows = tmpl.pattern.tiles_rows;
    ro.tiles_cols = tmpl.pattern.tiles_cols;
    const int ppc = tmpl.psf.pixels_per_cell, m = ro.n * ppc;
    check_psf_memory(ro.n, ppc, 8, 4);
    const Kernel kernel = mask_kernel(tmpl);
    // The model compute_mask_metrics builds for the first level: the same numbers as the rows.
    const ComplexPlane kernel_otf = expand_half_spectrum(kernel_spectrum(kernel, ro.n, ppc), m);
    const AnalyticWienerModel model(kernel_otf, context.prior(m), s.metrics.noise.front().model);
    const WeightChoice& nsr = s.metrics.simulation.wiener_nsr;
    const auto evaluate = [&](const ComplexPlane& spectrum) {
        if (figure == "analytic_mmse_psnr_db")
            return model.evaluate(spectrum, {WienerFilterKind::kOptimal, 0.0}).psnr_db;
        return nsr.tuned
                   ? model.evaluate_tuned_nsr(spectrum).psnr_db
                   : model.evaluate(spectrum, {WienerFilterKind::kFixedNsr, nsr.value}).psnr_db;
    };
    std::vector<Pattern> patterns;
    std::vector<double> psnr;
    for (int i = 0; i < count; ++i) {
        std::mt19937_64 rng(s.seed + static_cast<std::uint64_t>(i));
        patterns.push_back(random_sparse_pattern(ro, rng));
        psnr.push_back(evaluate(pattern_spectrum(patterns.back())));
        if (progress) progress(i + 1, count);
    }
    std::vector<int> order(static_cast<std::size_t>(count));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return psnr[static_cast<std::size_t>(a)] < psnr[static_cast<std::size_t>(b)];
    });
    const int median = order[static_cast<std::size_t>((count - 1) / 2)];
    RandomMedian out;
    out.count = count;
    out.figure = figure;
    out.median_standard_error_db = median_estimate(psnr).standard_error;
    out.median_seed = s.seed + static_cast<std::uint64_t>(median);
    out.min_psnr_db = psnr[static_cast<std::size_t>(order.front())];
    out.max_psnr_db = psnr[static_cast<std::size_t>(order.back())];
    out.median_psnr_db = psnr[static_cast<std::size_t>(median)];
    Mask mask = tmpl;
    mask.pattern = patterns[static_cast<std::size_t>(median)];
    mask.provenance = {};
    mask.provenance.seed = out.median_seed;
    mask.provenance.family = "random";
    mask.provenance.generator = PINMASK_GENERATOR("compare") " (random baseline)";
    std::ostringstream src;
    src << "median of " << count << " random valid masks by " << figure_words(figure) << " ("
        << figure << ", draw i from "
        << "seed " << s.seed << " + i, i = 0.." << count - 1 << "); this is seed "
        << out.median_seed << " (pinmask generate " << field_ref("family")
        << " random with this geometry and " << field_ref("seed") << " " << out.median_seed
        << " writes it)";
    out.entry = {"random median of " + std::to_string(count), "random-median", src.str(), mask};
    return out;
}

CompareEntry paper_like_baseline(const Mask& tmpl, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Mask mask = tmpl;
    mask.pattern = paper_pattern(rng);
    mask.provenance = {};
    mask.provenance.seed = seed;
    mask.provenance.family = "paper";
    mask.provenance.generator = PINMASK_GENERATOR("compare") " (paper-like baseline)";
    return {"paper-like (seed " + std::to_string(seed) + ")", "paper-like",
            "the paper's geometry (16 x 16 cells, K = 20, 2 x 2 tiles, spacing 2) placed by "
            "random sequential choice, seed " +
                std::to_string(seed),
            mask};
}

int mura_order_at_most(int n) {
    for (int p = n; p >= 5; --p)
        if (p % 4 == 1 && is_prime(p)) return p;
    return 0;
}

CompareEntry mura_baseline(const Mask& tmpl, int p) {
    Mask mask = tmpl;
    mask.pattern = mura_pattern(p, tmpl.pattern.min_spacing_cells, tmpl.pattern.tiles_rows,
                                tmpl.pattern.tiles_cols);
    mask.provenance = {};
    mask.provenance.family = "mura";
    mask.provenance.generator = PINMASK_GENERATOR("compare") " (MURA baseline)";
    mask.provenance.spacing_violations_allowed = true;
    std::ostringstream src;
    src << "MURA of order p = " << p << " (largest prime 4m + 1 <= n = " << tmpl.pattern.n << "), "
        << mask.pattern.pinholes.size() << " pinholes; breaks the spacing rule of "
        << tmpl.pattern.min_spacing_cells << " cells (MURAs are half open)";
    return {"MURA p = " + std::to_string(p) + " (breaks spacing)", "mura", src.str(), mask};
}

void CompareRunOptions::validate() const {
    pinmask::validate(settings);
    if (baseline_count < 1 || baseline_count > kMaxBaselineCount) {
        throw invalid_field(field_ref("baseline_count"), std::to_string(baseline_count),
                            "must be between 1 and 10000 (random draws; the median settles long "
                            "before)");
    }
}

CompareOutcome run_compare(std::vector<CompareEntry> entries, const CompareRunOptions& o,
                           const CompareProgress& progress) {
    o.validate();
    if (entries.empty()) throw InvalidInput("compare: no mask given");
    const CompareSettings& s = o.settings;
    if (progress) progress("building the scenes and the prior", 0, 0);
    MetricsContext context(s.metrics);
    CompareOutcome out;
    out.lead = compare_lead_figure(entries.front().mask, s.metrics.noise.front().model);
    const std::size_t given = entries.size();
    if (o.baselines) {
        const Mask tmpl = entries.front().mask;  // a copy: entries grows below
        try {
            RandomMedian rm = random_median_baseline(
                tmpl, o.baseline_count, s, context, out.lead.name, [&](int done, int total) {
                    if (progress) progress("random baseline", done, total);
                });
            std::ostringstream l;
            l.setf(std::ios::fixed);
            l.precision(2);
            l << "Baseline 'random median': " << rm.entry.source << ". " << figure_words(rm.figure)
              << " of the " << rm.count << " draws: min " << rm.min_psnr_db << ", median "
              << rm.median_psnr_db << " (standard error " << std::setprecision(3)
              << rm.median_standard_error_db << "), max " << std::setprecision(2) << rm.max_psnr_db
              << " dB.";
            out.baseline_lines.push_back(l.str());
            entries.push_back(rm.entry);
            rm.entry.mask = {};
            out.random = rm;
        } catch (const InvalidInput& e) {
            out.random_skipped = e.what();
            out.baseline_lines.push_back(std::string("random baseline left out: ") + e.what());
        }
        entries.push_back(paper_like_baseline(tmpl, s.seed));
        out.baseline_lines.push_back("Baseline 'paper-like': " + entries.back().source + ".");
        out.mura_order = mura_order_at_most(tmpl.pattern.n);
        if (out.mura_order > 0) {
            entries.push_back(mura_baseline(tmpl, out.mura_order));
            out.baseline_lines.push_back("Baseline 'MURA': " + entries.back().source + ".");
        } else {
            out.mura_skipped = "MURA baseline left out: no prime p = 4m + 1 <= n = " +
                               std::to_string(tmpl.pattern.n);
            out.baseline_lines.push_back(out.mura_skipped + ".");
        }
    }
    // A baseline can coincide with a given mask (e.g. generate's paper family with the same
    // seed); say so rather than leave two identical rows unexplained.
    for (std::size_t i = given; i < entries.size(); ++i) {
        for (std::size_t k = 0; k < given; ++k) {
            if (geometry_hash(entries[i].mask) == geometry_hash(entries[k].mask)) {
                entries[i].source += "; same geometry as " + entries[k].name;
                break;
            }
        }
    }
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (progress) progress("mask", static_cast<int>(i), static_cast<int>(entries.size()));
        out.results.push_back(compare_mask(entries[i], s, context));
    }
    add_differences(out);
    const Provenance& p = entries.front().mask.provenance;
    const auto recorded = p.scores.find(out.lead.name);
    const double computed = row_figure(out.results.front().row, out.lead.name);
    if (recorded != p.scores.end() &&
        !(std::abs(recorded->second - computed) <= kSameFigureTolerance * std::abs(computed))) {
        std::ostringstream l;
        l.precision(4);
        l.setf(std::ios::fixed);
        l << "The first mask's file records " << out.lead.name << " = " << recorded->second
          << " dB; compare computes " << computed
          << " dB under its settings (noise, prior or NSR other than the search's).";
        out.lead_mismatch = l.str();
    }
    return out;
}

void require_same_camera(const Mask& first, const Mask& m, const std::string& path) {
    const Camera &a = first.camera, &b = m.camera;
    const std::pair<const char*, std::pair<double, double>> fields[] = {
        {"object_distance_m", {a.object_distance_m, b.object_distance_m}},
        {"lens_focal_m", {a.lens_focal_m, b.lens_focal_m}},
        {"sensor_distance_m", {a.sensor_distance_m, b.sensor_distance_m}},
        {"wavelength_m", {a.wavelength_m, b.wavelength_m}},
        {"pixel_pitch_m", {a.pixel_pitch_m, b.pixel_pitch_m}},
        {"pinhole_m", {a.pinhole_m, b.pinhole_m}},
        {"sensor_cols", {a.sensor_cols, b.sensor_cols}},
        {"sensor_rows", {a.sensor_rows, b.sensor_rows}}};
    for (const auto& [name, v] : fields) {
        if (v.first == v.second) continue;
        std::ostringstream s, f;
        s << v.second;
        f << v.first;
        throw invalid_field(path + ": optics." + name, s.str(),
                            "differs from the first mask's " + f.str() +
                                "; a comparison report is for one camera (compare masks of "
                                "other cameras in separate runs)");
    }
}

}  // namespace pinmask
