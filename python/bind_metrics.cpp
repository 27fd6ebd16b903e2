// Mask metrics. metrics() is the metric row `pinmask compare` prints (optimize/metrics/compare
// compare_mask over optimize/metrics/mask_metrics, the one metric set of score, compare and
// search). The other functions bind the library metrics one by one
// (optimize/metrics/autocorrelation, spectrum_metrics, analytic_error, simulated_metrics).
#include <cmath>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/autocorrelation.hpp"
#include "optimize/metrics/compare.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"
#include "optimize/simulate/scene_prior.hpp"
#include "optimize/simulate/scenes.hpp"
#include "python/common.hpp"
#include "python/level_args.hpp"
#include "python/metrics_common.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

CompareSettings compare_settings(std::vector<NoiseLevel> levels, PriorSpec prior,
                                 const std::vector<std::string>& scenes, const std::string& nsr,
                                 const std::string& tv_lambda, int tv_iterations,
                                 std::uint64_t seed) {
    CompareSettings s;
    MaskMetricsOptions& m = s.metrics;
    m.tv = true;
    m.noise = std::move(levels);
    m.prior = std::move(prior);
    // The scene and decoder spellings of score and compare (optimize/metrics/metric_spellings).
    m.scenes = scene_specs_from_names(scenes);
    m.simulation.seed = seed;
    set_decoder_settings(m.simulation, nsr, tv_lambda, tv_iterations);
    s.seed = seed;
    validate(s);
    return s;
}

py::dict row_dict(const CompareRow& r) {
    py::dict d;
    d["name"] = r.name;
    d["kind"] = r.kind;
    d["source"] = r.source;
    d["geometry_hash"] = r.geometry_hash;
    d["n"] = r.n;
    d["holes"] = r.holes;
    d["pixels_per_cell"] = r.pixels_per_cell;
    d["period_px"] = r.period_px;
    d["min_spacing_cells"] = r.min_spacing_cells;
    d["spacing_ok"] = r.spacing_ok;
    d["spacing_violations"] = r.spacing_violations;
    d["max_sidelobe"] = r.max_sidelobe;
    d["peak_to_sidelobe_ratio"] = r.peak_to_sidelobe_ratio;
    d["min_abs_pattern_spectrum"] = r.min_abs_pattern_spectrum;
    d["spectral_flatness"] = r.spectral_flatness;
    d["otf_condition_number"] = r.otf_condition_number;
    d["analytic_mmse_psnr_db"] = r.analytic_mmse_psnr_db;
    d["analytic_wiener_psnr_db"] = r.analytic_wiener_psnr_db;
    d["analytic_wiener_nsr"] = r.analytic_wiener_nsr;
    if (!std::isnan(r.analytic_robust_wiener_psnr_db))
        d["analytic_robust_wiener_psnr_db"] = r.analytic_robust_wiener_psnr_db;
    d["sim_wiener_psnr_db"] = r.sim_wiener_psnr_db;
    d["sim_wiener_ssim"] = r.sim_wiener_ssim;
    d["sim_wiener_nsr"] = r.sim_wiener_nsr;
    d["sim_tv_psnr_db"] = r.sim_tv_psnr_db;
    d["sim_tv_ssim"] = r.sim_tv_ssim;
    d["sim_tv_lambda"] = r.sim_tv_lambda;
    // Every level under score's keys (cli/options/analytic_setup metrics_json names them the same
    // way).
    for (const LevelMetrics& l : r.metrics.levels) {
        const std::string& k = l.level.key;
        if (l.analytic) {
            d[py::str("analytic_wiener_psnr_db_" + k)] = l.analytic->psnr_db;
            d[py::str("analytic_wiener_nsr_" + k)] = l.analytic->nsr;
            d[py::str("analytic_mmse_psnr_db_" + k)] = l.analytic->mmse_psnr_db;
        }
        if (l.robust) {
            d[py::str("analytic_robust_wiener_psnr_db_" + k)] = l.robust->psnr_db;
            d[py::str("analytic_robust_wiener_loss_db_" + k)] = l.robust->loss_db;
        }
        const std::pair<const char*, const std::optional<SimulatedQuality>*> sims[] = {
            {"wiener", &l.wiener}, {"tv", &l.tv}};
        for (const auto& [metric, q] : sims) {
            if (!*q) continue;
            const std::string name = std::string("sim_") + metric;  // simulated on the scenes
            d[py::str(name + "_psnr_db_" + k)] = (*q)->mean_psnr_db;
            d[py::str(name + "_ssim_" + k)] = (*q)->mean_ssim;
            d[py::str(name + (name == "sim_wiener" ? "_nsr_" : "_lambda_") + k)] = (*q)->weight;
        }
        if (l.depth) {
            d["depth_from_m"] = l.depth->from_m;
            d["depth_to_m"] = l.depth->to_m;
            d[py::str("depth_crb_rel_" + k)] = l.depth->crb_rel;
            d[py::str("depth_axial_fwhm_m_" + k)] = l.depth->axial_fwhm_m;
            d[py::str("depth_worst_distance_m_" + k)] = l.depth->worst_distance_m;
        }
    }
    return d;
}

namespace {

WienerFilterSpec filter_spec(const std::string& text) { return parse_wiener_filter(text); }

}  // namespace

void bind_metrics(py::module_& m) {
    m.def(
        "metrics",
        [](const py::handle& mask_obj, const py::object& snr_db,
           const std::vector<std::string>& scenes, int prior_scenes, const std::string& nsr,
           const std::string& tv_lambda, int tv_iterations, std::uint64_t seed,
           const std::string& name, const py::object& photons, std::optional<double> read_noise,
           std::optional<double> dark_current, std::optional<double> full_well,
           std::optional<int> bits, std::optional<double> optical_density, const py::object& prior,
           const std::optional<std::string>& robust) {
            const SensorSettings sensor{read_noise, dark_current, full_well, optical_density, bits};
            CompareSettings s = compare_settings(noise_levels_arg(snr_db, photons, sensor, {30.0}),
                                                 prior_arg(prior, prior_scenes), scenes, nsr,
                                                 tv_lambda, tv_iterations, seed);
            // robust: score's parser (InvalidInput naming `robust` and the key).
            if (robust) s.metrics.robust = parse_fabrication_errors(*robust);
            const Mask mk = mask_arg(mask_obj, true);
            CompareEntry e{name, "input",
                           py::isinstance<py::str>(mask_obj) ? mask_obj.cast<std::string>()
                                                             : std::string("python"),
                           mk};
            CompareResult r;
            {
                py::gil_scoped_release release;
                MetricsContext context(s.metrics);
                r = compare_mask(e, s, context);
            }
            return as_result(row_dict(r.row));
        },
        py::arg("mask"), py::arg("snr_db") = py::none(),
        py::arg("scenes") = std::vector<std::string>{"letter-R", "usaf", "siemens-star"},
        py::arg("prior_scenes") = kDefaultPriorScenes, py::arg("nsr") = "tuned",
        py::arg("tv_lambda") = "1e-3", py::arg("tv_iterations") = 200, py::arg("seed") = 1,
        py::arg("name") = "mask", py::arg("photons") = py::none(),
        py::arg("read_noise") = py::none(), py::arg("dark_current") = py::none(),
        py::arg("full_well") = py::none(), py::arg("bits") = py::none(),
        py::arg("optical_density") = py::none(), py::arg("prior") = "natural",
        py::arg("robust") = py::none(),
        R"(The metric row of `pinmask compare` for one mask (optimize/metrics/compare over
optimize/metrics/mask_metrics, the set score and search use; same settings, same numbers): sidelobes,
spectrum, OTF condition, analytic PSNR over the prior (dB; analytic_mmse_psnr_db: the
per-frequency optimal filter, analytic_wiener_psnr_db: Wiener at the nsr, analytic_wiener_nsr),
simulated Wiener and TV-L2 PSNR (dB) and SSIM over `scenes` (sim_wiener_psnr_db, sim_tv_psnr_db,
...).
Noise (as --snr / --photons and the sensor flags): snr_db, Gaussian SNR in dB, a number or a
list (None: 30 dB); or photons, the photon model at that many electrons per pixel through one
pinhole (a number or a list), with read_noise (rms electrons), dark_current (mean electrons per
pixel), full_well (electrons), bits (ADC, needs full_well) and optical_density (film OD).
The unsuffixed keys are the first level's; every level is also under score's keys
(analytic_mmse_psnr_db_snr30, sim_wiener_psnr_db_ph100, ...).
Prior of the analytic error (as --prior / --prior-scenes): 'natural' | 'text' | 'stars' or image
files (a list of paths or one comma-separated string), prior_scenes sample scenes (1..4096).
nsr and tv_lambda: 'tuned' or a number > 0.
robust (as --robust): 'size=44um,jitter=2um,missing=0.01' (any subset) adds the analytic Wiener
PSNR expected under those fabrication errors, decoded with the nominal PSF, and its loss:
analytic_robust_wiener_psnr_db (first level) and per level
analytic_robust_wiener_psnr_db_<level>, analytic_robust_wiener_loss_db_<level>, score's keys and
numbers.)");

    m.def(
        "sidelobes",
        [](const Pattern& p) {
            validate(p, true);
            const SidelobeMetrics s = sidelobe_metrics_from_spectrum(pattern_spectrum(p));
            py::dict d;
            d["peak"] = s.peak;
            d["max_sidelobe"] = s.max_sidelobe;
            d["mean_sidelobe"] = s.mean_sidelobe;
            d["integrated_sidelobe_level"] = s.integrated_sidelobe_level;
            d["peak_to_sidelobe_ratio"] = s.peak_to_sidelobe_ratio;
            return as_result(d);
        },
        py::arg("pattern"),
        "Torus autocorrelation sidelobes of a pattern: peak R(0) = K, max sidelobe (counts), "
        "mean sidelobe, integrated sidelobe level sum R(d)^2 / K^2 (d != 0), peak/max ratio.");
    m.def(
        "autocorrelation",
        [](const Pattern& p) {
            validate(p, true);
            const std::vector<int> r = autocorrelation_from_spectrum(pattern_spectrum(p));
            py::array_t<int> a({p.n, p.n});
            std::copy(r.begin(), r.end(), a.mutable_data());
            return a;
        },
        py::arg("pattern"), "R(dr, dc) on the n x n torus as an int array, R(0, 0) = K.");
    m.def(
        "spectrum_metrics",
        [](const Pattern& p) {
            validate(p, true);
            const PatternSpectrumMetrics s = pattern_spectrum_metrics(pattern_spectrum(p));
            py::dict d;
            d["min_abs_pattern_spectrum"] = s.min_abs_pattern_spectrum;
            d["spectral_flatness"] = s.spectral_flatness;
            d["open_fraction"] = s.open_fraction;
            d["light_gain"] = s.light_gain;
            return as_result(d);
        },
        py::arg("pattern"),
        "Spectrum of the n x n pattern DFT P^: min |P^(k)| over k != 0, spectral flatness "
        "(geometric/arithmetic mean of |P^|^2), open fraction K/n^2, light gain K.");

    m.def(
        "analytic_error",
        [](const py::handle& mask_obj, std::optional<double> snr_db, std::optional<double> photons,
           std::optional<double> read_noise, std::optional<double> dark_current,
           std::optional<double> full_well, std::optional<int> bits,
           std::optional<double> optical_density, const std::string& filter, int prior_scenes,
           std::uint64_t prior_first_seed) {
            const NoiseModel noise = noise_model(
                {snr_db, photons, read_noise, dark_current, full_well, optical_density, bits});
            if (noise.kind == NoiseKind::kNone)
                throw invalid_field("snr_db", "inf", "the analytic error needs noise");
            const Mask mk = mask_arg(mask_obj, true);
            if (prior_scenes < 1)
                throw invalid_field(field_ref("prior.count"), std::to_string(prior_scenes),
                                    "must be >= 1");
            const bool tuned = filter == "tuned";
            const WienerFilterSpec f = tuned ? WienerFilterSpec{} : filter_spec(filter);
            AnalyticError e;
            {
                py::gil_scoped_release release;
                const int n = mk.pattern.n, ppc = mk.psf.pixels_per_cell, mp = n * ppc;
                const Kernel k = mask_kernel(mk);
                const AnalyticWienerModel model(
                    expand_half_spectrum(kernel_spectrum(k, n, ppc), mp),
                    natural_scene_prior(mp, mp, prior_scenes, prior_first_seed), noise);
                const ComplexPlane ps = pattern_spectrum(mk.pattern);
                e = tuned ? model.evaluate_tuned_nsr(ps) : model.evaluate(ps, f);
            }
            py::dict d;
            d["mse"] = e.mse;
            d["psnr_db"] = e.psnr_db;
            d["noise_variance"] = e.noise_variance;
            d["mean_square_capture"] = e.mean_square_capture;
            d["nsr"] = e.nsr;
            return as_result(d);
        },
        py::arg("mask"), py::arg("snr_db") = py::none(), py::arg("photons") = py::none(),
        py::arg("read_noise") = py::none(), py::arg("dark_current") = py::none(),
        py::arg("full_well") = py::none(), py::arg("bits") = py::none(),
        py::arg("optical_density") = py::none(), py::arg("filter") = "optimal",
        py::arg("prior_scenes") = kDefaultPriorScenes,
        py::arg("prior_first_seed") = kPriorFirstSeed,
        "Expected Wiener error in closed form (optimize/metrics/analytic_error): filter 'optimal' "
        "(per-frequency), 'nsr:VALUE' (deconvwnr's fixed NSR) or 'tuned' (the NSR minimising "
        "the expected MSE); prior: the mean |X^|^2 of prior_scenes natural 1/f textures (seeds "
        "prior_first_seed..); noise as simulate() (Gaussian snr_db, default 30, or photons ...). "
        "Returns {mse (per pixel, scene in [0, 1]), psnr_db, noise_variance, "
        "mean_square_capture, nsr}.");

    m.def(
        "simulated_quality",
        [](const py::handle& mask_obj, const std::vector<std::string>& scenes,
           const std::string& decoder, std::optional<double> snr_db, std::optional<double> photons,
           std::optional<double> read_noise, std::optional<double> dark_current,
           std::optional<double> full_well, std::optional<int> bits,
           std::optional<double> optical_density, const std::string& weight, int noise_seeds,
           std::uint64_t seed, int tv_iterations) {
            const NoiseModel noise = noise_model(
                {snr_db, photons, read_noise, dark_current, full_well, optical_density, bits});
            if (noise.kind == NoiseKind::kNone)
                throw invalid_field("snr_db", "inf", "simulated quality needs noise");
            if (decoder != "wiener" && decoder != "tv")
                throw invalid_field("decoder", decoder, "must be wiener or tv");
            const Mask mk = mask_arg(mask_obj, true);
            SimulatedMetricsOptions so;
            so.noise_seeds = noise_seeds;
            so.seed = seed;
            so.tv_iterations = tv_iterations;
            const WeightChoice w = parse_weight_choice(weight, "weight");
            (decoder == "wiener" ? so.wiener_nsr : so.tv_lambda) = w;
            so.validate();
            SimulatedQuality q;
            {
                py::gil_scoped_release release;
                const Plane psf = mask_psf(mk);
                const int mp = static_cast<int>(psf.rows());
                std::vector<NamedScene> named;
                for (const auto& s : scenes)
                    named.push_back({s, make_scene(scene_from_name(s), mp, mp)});
                q = simulated_quality(
                    psf, named, noise, static_cast<int>(mk.pattern.pinholes.size()),
                    mk.pattern.n * mk.pattern.n,
                    decoder == "wiener" ? SimulatedDecoder::kWiener : SimulatedDecoder::kTv, so);
            }
            py::dict d;
            d["weight"] = q.weight;
            d["mean_psnr_db"] = q.mean_psnr_db;
            d["mean_ssim"] = q.mean_ssim;
            py::dict per;
            for (const auto& s : q.scenes)
                per[py::str(s.scene)] = py::make_tuple(s.psnr_db, s.ssim);
            d["scenes"] = per;
            d["decodes"] = q.decodes;
            return as_result(d);
        },
        py::arg("mask"), py::arg("scenes") = std::vector<std::string>{"letter-R", "usaf"},
        py::arg("decoder") = "wiener", py::arg("snr_db") = py::none(),
        py::arg("photons") = py::none(), py::arg("read_noise") = py::none(),
        py::arg("dark_current") = py::none(), py::arg("full_well") = py::none(),
        py::arg("bits") = py::none(), py::arg("optical_density") = py::none(),
        py::arg("weight") = "tuned", py::arg("noise_seeds") = 1, py::arg("seed") = 0,
        py::arg("tv_iterations") = 200,
        "Simulated reconstruction quality over one period (optimize/metrics/simulated_metrics): "
        "each "
        "scene through the mask's PSF with noise (as simulate()), decoded by wiener or tv with "
        "weight (NSR or lambda) 'tuned' or a number > 0, noise_seeds draws from seed. Returns "
        "{weight, mean_psnr_db, mean_ssim, scenes: {name: (psnr_db, ssim)}, decodes}.");
}

}  // namespace pinmask::python
