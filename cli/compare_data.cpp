#include "cli/compare_data.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include "cli/analytic_setup.hpp"
#include "core/error.hpp"
#include "core/fft.hpp"
#include "decode/decoder.hpp"
#include "design/families.hpp"
#include "design/kernel_model.hpp"
#include "design/mura.hpp"
#include "design/psf.hpp"
#include "design/random_sparse.hpp"
#include "optimize/autocorrelation.hpp"
#include "optimize/image_quality.hpp"
#include "optimize/noise_model.hpp"
#include "optimize/simulate.hpp"
#include "optimize/spectrum_metrics.hpp"

namespace pinmask::cli {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

SimulatedMetricsOptions simulation_options(const CompareSettings& s) {
    SimulatedMetricsOptions o;
    o.noise_seeds = 1;
    o.seed = s.seed;
    o.wiener_nsr = s.wiener_nsr;
    o.tv_lambda = s.tv_lambda;
    o.tv_iterations = s.tv_iterations;
    return o;
}

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
    so.noise.kind = NoiseKind::kGaussianSnr;
    so.noise.snr_db = s.snr_db;
    so.seed = s.seed;
    const int holes = static_cast<int>(mask.pattern.pinholes.size());
    const SimulatedCapture cap = simulate_capture(shown.image, psf, holes, n * n, so);
    Image wiener, tv;
    for (const Plane& ch : cap.capture.channels) {
        DecodeOptions w;
        w.method = DecodeMethod::kWiener;
        w.nsr = r.row.wiener_nsr;
        wiener.channels.push_back(decode_plane(ch, psf, w).image);
        DecodeOptions t;
        t.method = DecodeMethod::kTv;
        t.lambda = r.row.tv_lambda;
        t.max_iterations = s.tv_iterations;
        t.tolerance = SimulatedMetricsOptions{}.tv_tolerance;
        t.record_history = false;
        const DecodeResult d = decode_plane(ch, psf, t);
        p.tv_iterations = std::max(p.tv_iterations, d.iterations);
        tv.channels.push_back(d.image);
    }
    p.scene_name = shown.name;
    p.scene = channel_mean(shown.image);
    p.capture = channel_mean(cap.capture);
    p.wiener = channel_mean(wiener);
    p.tv = channel_mean(tv);
    p.capture_sigma =
        sigma_for_snr(cap.clean.channels[0].square().mean(), s.snr_db);  // as add_noise draws it
    const bool has_ssim = m >= kSsimWindow;
    p.wiener_psnr_db = psnr_db(wiener, shown.image);
    p.tv_psnr_db = psnr_db(tv, shown.image);
    p.wiener_ssim = has_ssim ? ssim(wiener, shown.image) : kNan;
    p.tv_ssim = has_ssim ? ssim(tv, shown.image) : kNan;
}

}  // namespace

void validate(const CompareSettings& s) {
    if (!std::isfinite(s.snr_db))
        throw invalid_field("--snr", std::to_string(s.snr_db), "must be finite");
    if (s.scenes.empty()) throw invalid_field("--scenes", "''", "needs at least one scene");
    if (s.prior_scenes < 1) {
        throw invalid_field("--prior-scenes", std::to_string(s.prior_scenes), "must be >= 1");
    }
    if (s.tv_iterations < 1) {
        throw invalid_field("--tv-iters", std::to_string(s.tv_iterations), "must be >= 1");
    }
    simulation_options(s).validate();
}

const std::vector<NamedScene>& SceneCache::at(int m, const std::vector<SceneSpec>& specs) {
    auto it = cache_.find(m);
    if (it != cache_.end()) return it->second;
    std::vector<NamedScene> scenes;
    for (const SceneSpec& s : specs) scenes.push_back({scene_name(s), make_scene(s, m, m)});
    return cache_.emplace(m, std::move(scenes)).first->second;
}

CompareResult compare_mask(const CompareEntry& e, const CompareSettings& s, SceneCache& cache) {
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

    const ComplexPlane spectrum = pattern_spectrum(mask.pattern);
    const std::vector<int> ac = autocorrelation_from_spectrum(spectrum);
    const SidelobeMetrics sl = sidelobe_metrics(ac, n);
    row.max_sidelobe = sl.max_sidelobe;
    row.peak_to_sidelobe_ratio = sl.peak_to_sidelobe_ratio;
    const PatternSpectrumMetrics ps = pattern_spectrum_metrics(spectrum);
    row.min_abs_pattern_spectrum = ps.min_abs_pattern_spectrum;
    row.spectral_flatness = ps.spectral_flatness;

    const Kernel kernel = mask_kernel(mask);
    r.pictures.kernel = kernel_text(kernel);
    const ComplexPlane kernel_half = kernel_spectrum(kernel, n, ppc);
    const ComplexPlane kernel_otf = expand_half_spectrum(kernel_half, m);
    row.otf_condition_number = otf_condition(spectrum, kernel_otf).condition_number;
    const AnalyticWienerModel model =
        analytic_wiener_model(kernel, n, ppc, s.snr_db, s.prior_scenes);
    row.analytic_wiener_psnr_db = model.evaluate(spectrum, s.analytic_filter).psnr_db;

    const Plane psf = synthesize_psf(mask.pattern, kernel, ppc);
    const std::vector<NamedScene>& scenes = cache.at(m, s.scenes);
    const SimulatedMetricsOptions so = simulation_options(s);
    const SimulatedQuality w =
        simulated_quality(psf, scenes, s.snr_db, SimulatedDecoder::kWiener, so);
    row.wiener_psnr_db = w.mean_psnr_db;
    row.wiener_ssim = w.mean_ssim;
    row.wiener_nsr = w.weight;
    const SimulatedQuality t = simulated_quality(psf, scenes, s.snr_db, SimulatedDecoder::kTv, so);
    row.tv_psnr_db = t.mean_psnr_db;
    row.tv_ssim = t.mean_ssim;
    row.tv_lambda = t.weight;

    // The OTF from the spectra above (psf_otf would recompute both).
    const ComplexPlane otf =
        expand_half_spectrum(combine_spectra(spectrum, kernel_half, row.holes), m);
    fill_pictures(r, mask, psf, otf, ac, scenes.front(), s);
    return r;
}

RandomMedian random_median_baseline(const Mask& tmpl, int count, const CompareSettings& s,
                                    SceneCache& cache) {
    if (count < 1) throw invalid_field("--baseline-count", std::to_string(count), "must be >= 1");
    RandomSparseOptions ro;
    ro.n = tmpl.pattern.n;
    ro.holes = static_cast<int>(tmpl.pattern.pinholes.size());
    ro.min_spacing_cells = tmpl.pattern.min_spacing_cells;
    ro.tiles_rows = tmpl.pattern.tiles_rows;
    ro.tiles_cols = tmpl.pattern.tiles_cols;
    const int ppc = tmpl.psf.pixels_per_cell, m = ro.n * ppc;
    check_psf_memory(ro.n, ppc, 8, 4);
    const Kernel kernel = mask_kernel(tmpl);
    const std::vector<NamedScene>& scenes = cache.at(m, s.scenes);
    const SimulatedMetricsOptions so = simulation_options(s);
    std::vector<Pattern> patterns;
    std::vector<double> psnr;
    for (int i = 0; i < count; ++i) {
        std::mt19937_64 rng(s.seed + static_cast<std::uint64_t>(i));
        patterns.push_back(random_sparse_pattern(ro, rng));
        const Plane psf = synthesize_psf(patterns.back(), kernel, ppc);
        psnr.push_back(
            simulated_quality(psf, scenes, s.snr_db, SimulatedDecoder::kWiener, so).mean_psnr_db);
    }
    std::vector<int> order(static_cast<std::size_t>(count));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return psnr[static_cast<std::size_t>(a)] < psnr[static_cast<std::size_t>(b)];
    });
    const int median = order[static_cast<std::size_t>((count - 1) / 2)];
    RandomMedian out;
    out.count = count;
    out.median_seed = s.seed + static_cast<std::uint64_t>(median);
    out.min_psnr_db = psnr[static_cast<std::size_t>(order.front())];
    out.max_psnr_db = psnr[static_cast<std::size_t>(order.back())];
    out.median_psnr_db = psnr[static_cast<std::size_t>(median)];
    Mask mask = tmpl;
    mask.pattern = patterns[static_cast<std::size_t>(median)];
    mask.provenance = {};
    mask.provenance.seed = out.median_seed;
    mask.provenance.family = "random";
    mask.provenance.generator = "pinmask compare 0.1.0 (random baseline)";
    std::ostringstream src;
    src << "median of " << count << " random valid masks by simulated Wiener PSNR (draw i from "
        << "seed " << s.seed << " + i, i = 0.." << count - 1 << "); this is seed "
        << out.median_seed << " (pinmask generate --family random with this geometry and --seed "
        << out.median_seed << " writes it)";
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
    mask.provenance.generator = "pinmask compare 0.1.0 (paper-like baseline)";
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
    mask.provenance.generator = "pinmask compare 0.1.0 (MURA baseline)";
    mask.provenance.spacing_violations_allowed = true;
    std::ostringstream src;
    src << "MURA of order p = " << p << " (largest prime 4m + 1 <= n = " << tmpl.pattern.n << "), "
        << mask.pattern.pinholes.size() << " pinholes; breaks the spacing rule of "
        << tmpl.pattern.min_spacing_cells << " cells (MURAs are half open)";
    return {"MURA p = " + std::to_string(p) + " (breaks spacing)", "mura", src.str(), mask};
}

}  // namespace pinmask::cli
