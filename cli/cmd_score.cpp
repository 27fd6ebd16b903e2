// `pinmask score`: metrics of one or more masks, one row per mask. Only what --metrics asks for
// is computed: sidelobes and pattern-spectrum metrics need only the n x n pattern DFT; the OTF
// condition and the analytic error need the kernel's spectrum over one period; simulated
// metrics (wiener, tv) render scenes at one period and run the decoder. The numerics live in
// optimize/ (autocorrelation, spectrum_metrics, analytic_error, simulated_metrics); this file
// parses flags, orders the work, and prints.
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/analytic_setup.hpp"
#include "cli/command.hpp"
#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "cli/noise_options.hpp"
#include "core/error.hpp"
#include "core/fft.hpp"
#include "core/resource_limits.hpp"
#include "core/units.hpp"
#include "design/kernel.hpp"
#include "design/kernel_model.hpp"
#include "design/psf.hpp"
#include "optimize/analytic_error.hpp"
#include "optimize/autocorrelation.hpp"
#include "optimize/scene_prior.hpp"
#include "optimize/scenes.hpp"
#include "optimize/simulated_metrics.hpp"
#include "optimize/spectrum_metrics.hpp"

namespace pinmask::cli {
namespace {

using io::json_strict::finite_or_null;

constexpr int kPriorScenes = 64;                 // natural scenes averaged for the default prior
constexpr std::uint64_t kPriorFirstSeed = 1000;  // prior seeds 1000..1063, apart from the scored
constexpr std::uint64_t kNaturalSceneSeed = 0;   // the scored "natural" scene

// The period PSF (m x m, sum 1, m = n * pixels per cell) and the single-pinhole kernel's full
// m x m spectrum, from the PSF synthesis of design/.
struct PeriodOptics {
    Plane psf;
    ComplexPlane kernel_otf;
    std::string description;
};

PeriodOptics period_optics(const Mask& mask) {
    const int n = mask.pattern.n, ppc = mask.psf.pixels_per_cell;
    check_psf_memory(n, ppc, 4, 3);  // PSF, kernel, two scene planes; kernel and OTF spectra
    const Kernel kernel = mask_kernel(mask);
    PeriodOptics o;
    o.psf = synthesize_psf(mask.pattern, kernel, ppc);
    o.kernel_otf = expand_half_spectrum(kernel_spectrum(kernel, n, ppc), n * ppc);
    std::ostringstream s;
    s << kernel_model_name(kernel.model) << " (" << kernel.model_reason << "), "
      << kernel.values.rows() << " x " << kernel.values.cols() << " px, enclosed energy "
      << kernel.enclosed_energy;
    o.description = s.str();
    return o;
}

struct ScoreOptions {
    std::vector<std::string> masks;
    std::string scenes = "letter-R,usaf,natural";
    std::string snr = "20,30,40";
    std::string photons;  // --photons LIST: the photon model instead of --snr
    SensorFlags sensor;
    std::string metrics = "sidelobes,spectrum,analytic,wiener";
    std::string nsr = "0.01";
    std::string tv_lambda = "1e-3";
    int tv_iterations = 200;
    int seeds = 1;
    std::uint64_t seed = 0;
    bool allow_violations = false;
    bool json = false;
    bool explain = false;
};

const std::vector<std::string> kMetricNames{"sidelobes", "spectrum", "analytic", "wiener", "tv"};

std::vector<std::string> split_list(const std::string& text, const std::string& flag) {
    std::vector<std::string> out;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, ',')) {
        if (item.empty()) throw invalid_field(flag, "'" + text + "'", "has an empty list item");
        out.push_back(item);
    }
    if (out.empty()) throw invalid_field(flag, "''", "needs at least one item");
    return out;
}

// One noise level of the table: a Gaussian SNR or a photon level, with the suffix of its keys
// ("30" -> "snr30", "27.5" -> "snr27.5"; 1000 photons per pinhole -> "ph1000").
struct NoiseLevel {
    NoiseModel model;
    std::string key;
};

std::string number_text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

struct Plan {
    std::set<std::string> metrics;
    std::vector<NoiseLevel> noise;
    std::string noise_text;  // for --explain: "SNR 20,30 dB" or "the photon model at ..."
    std::vector<SceneSpec> scenes;
    WeightChoice nsr, tv_lambda;
    bool has(const std::string& m) const { return metrics.count(m) > 0; }
    bool simulated() const { return has("wiener") || has("tv"); }
    bool needs_optics() const { return has("analytic") || simulated() || has("spectrum"); }
};

Plan make_plan(const ScoreOptions& o, const CLI::App& cmd) {
    Plan p;
    for (const std::string& m : split_list(o.metrics, "--metrics")) {
        bool known = false;
        for (const auto& k : kMetricNames) known = known || k == m;
        if (!known) {
            throw invalid_field("--metrics", m,
                                "must be one of sidelobes, spectrum, analytic, wiener, tv");
        }
        p.metrics.insert(m);
    }
    if (!o.photons.empty()) {
        if (cmd.count("--snr") > 0)
            throw invalid_field("--snr", o.snr, "cannot be combined with --photons");
        std::string levels;
        for (const std::string& s : split_list(o.photons, "--photons")) {
            const double ppp = parse_number(s, "--photons");
            p.noise.push_back({photon_model(ppp, o.sensor), "ph" + number_text(ppp)});
            levels += (levels.empty() ? "" : ",") + number_text(ppp);
        }
        const NoiseModel& m = p.noise.front().model;
        p.noise_text =
            "the photon model at " + levels + " electrons per pixel per pinhole (read noise " +
            number_text(m.read_noise_e) + " e, dark current " + number_text(m.dark_current_e) +
            " e, film OD " + number_text(m.film_optical_density) + ")";
    } else {
        refuse_sensor_flags_without_photons(cmd);
        std::string levels;
        for (const std::string& s : split_list(o.snr, "--snr")) {
            NoiseLevel level;
            level.model.kind = NoiseKind::kGaussianSnr;
            level.model.snr_db = parse_number(s, "--snr");
            validate(level.model);
            level.key = "snr" + number_text(level.model.snr_db);
            p.noise.push_back(level);
            levels += (levels.empty() ? "" : ",") + number_text(level.model.snr_db);
        }
        p.noise_text = "Gaussian noise at SNR " + levels + " dB";
    }
    for (const std::string& s : split_list(o.scenes, "--scenes")) {
        SceneSpec spec = scene_from_name(s);
        if (spec.kind == SceneKind::kNatural) spec.seed = kNaturalSceneSeed;
        p.scenes.push_back(spec);
    }
    p.nsr = parse_weight_choice(o.nsr, "--nsr");
    p.tv_lambda = parse_weight_choice(o.tv_lambda, "--tv-lambda");
    if (o.seeds < 1) throw invalid_field("--seeds", std::to_string(o.seeds), "must be >= 1");
    if (o.tv_iterations < 1) {
        throw invalid_field("--tv-iters", std::to_string(o.tv_iterations), "must be >= 1");
    }
    return p;
}

// Per period size: the rendered scenes and the analytic prior, built once and shared by masks.
struct PeriodData {
    std::vector<NamedScene> scenes;
    std::unique_ptr<ScenePrior> prior;
};

class Explain {
  public:
    void add(const std::string& line) {
        for (const auto& l : lines_)
            if (l == line) return;
        lines_.push_back(line);
    }
    const std::vector<std::string>& lines() const { return lines_; }

  private:
    std::vector<std::string> lines_;
};

std::string join(const std::vector<double>& v) {
    std::ostringstream s;
    for (std::size_t i = 0; i < v.size(); ++i) s << (i ? "," : "") << v[i];
    return s.str();
}

// Scenes rendered at the period and the prior (from the scene files when any, else natural).
PeriodData& period_data(std::map<int, PeriodData>& cache, int m, const Plan& plan,
                        Explain& explain) {
    auto it = cache.find(m);
    if (it != cache.end()) return it->second;
    check_memory(8.0 * m * m * (3.0 * plan.scenes.size() + 4.0), "score scenes at the period");
    PeriodData d;
    const std::string size = std::to_string(m) + " x " + std::to_string(m);
    if (plan.simulated()) {
        for (const SceneSpec& s : plan.scenes)
            d.scenes.push_back({scene_name(s), make_scene(s, m, m)});
        explain.add("scenes: rendered at one " + size + " period (grey scenes as one channel)");
    }
    if (plan.has("analytic")) {
        std::vector<Plane> files;
        std::string names;
        for (const SceneSpec& s : plan.scenes) {
            if (s.kind != SceneKind::kFile) continue;
            for (Plane& ch : make_scene(s, m, m).channels) files.push_back(std::move(ch));
            names += (names.empty() ? "" : ", ") + s.path.string();
        }
        if (!files.empty()) {
            d.prior = std::make_unique<ScenePrior>(
                scene_prior_from_images(files, "scene files: " + names));
        } else {
            d.prior = std::make_unique<ScenePrior>(
                natural_scene_prior(m, m, kPriorScenes, kPriorFirstSeed, 1.0));
        }
        explain.add("analytic prior at " + size + ": " + d.prior->source + " (" +
                    std::to_string(d.prior->sample_count) + " images)");
    }
    return cache.emplace(m, std::move(d)).first->second;
}

nlohmann::ordered_json score_mask(const std::string& path, const ScoreOptions& o, const Plan& plan,
                                  std::map<int, PeriodData>& cache, Explain& explain) {
    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    const Mask mask = io::read_mask_file(path, ro);
    const int n = mask.pattern.n, m = n * mask.psf.pixels_per_cell;
    nlohmann::ordered_json row;
    row["mask"] = path;
    row["geometry_hash"] = geometry_hash(mask);
    row["n"] = n;
    row["holes"] = mask.pattern.pinholes.size();
    row["pixels_per_cell"] = mask.psf.pixels_per_cell;
    row["period_px"] = m;
    const ComplexPlane spectrum = pattern_spectrum(mask.pattern);

    if (plan.has("sidelobes")) {
        const SidelobeMetrics s = sidelobe_metrics_from_spectrum(spectrum);
        row["peak_autocorrelation"] = s.peak;
        row["max_sidelobe"] = s.max_sidelobe;
        row["mean_sidelobe"] = s.mean_sidelobe;
        row["integrated_sidelobe_level"] = s.integrated_sidelobe_level;
        row["peak_to_sidelobe_ratio"] = finite_or_null(s.peak_to_sidelobe_ratio);
    }
    PeriodOptics optics;
    if (plan.needs_optics()) {
        optics = period_optics(mask);
        explain.add("kernel of " + path + ": " + optics.description);
    }
    if (plan.has("spectrum")) {
        const PatternSpectrumMetrics s = pattern_spectrum_metrics(spectrum);
        row["min_abs_pattern_spectrum"] = s.min_abs_pattern_spectrum;
        row["spectral_flatness"] = s.spectral_flatness;
        row["open_fraction"] = s.open_fraction;
        row["light_gain"] = s.light_gain;
        const OtfCondition c = otf_condition(spectrum, optics.kernel_otf);
        row["otf_condition_number"] = finite_or_null(c.condition_number);
        row["otf_passband_frequencies"] = c.passband_frequencies;
    }
    const bool need_period = plan.has("analytic") || plan.simulated();
    PeriodData* data = need_period ? &period_data(cache, m, plan, explain) : nullptr;
    if (plan.has("analytic")) {
        for (const NoiseLevel& level : plan.noise) {
            const AnalyticWienerModel model(optics.kernel_otf, *data->prior, level.model);
            const AnalyticError e =
                plan.nsr.tuned
                    ? model.evaluate_tuned_nsr(spectrum)
                    : model.evaluate(spectrum, {WienerFilterKind::kFixedNsr, plan.nsr.value});
            const AnalyticError best = model.evaluate(spectrum, {WienerFilterKind::kOptimal, 0.0});
            const std::string& k = level.key;
            row["analytic_wiener_psnr_db_" + k] = finite_or_null(e.psnr_db);
            row["analytic_wiener_nsr_" + k] = e.nsr;
            row["analytic_optimal_wiener_psnr_db_" + k] = finite_or_null(best.psnr_db);
        }
    }
    SimulatedMetricsOptions so;
    so.noise_seeds = o.seeds;
    so.seed = o.seed;
    so.wiener_nsr = plan.nsr;
    so.tv_lambda = plan.tv_lambda;
    so.tv_iterations = o.tv_iterations;
    nlohmann::ordered_json per_scene = nlohmann::ordered_json::object();
    for (const auto& [metric, decoder] :
         {std::pair{std::string("wiener"), SimulatedDecoder::kWiener},
          std::pair{std::string("tv"), SimulatedDecoder::kTv}}) {
        if (!plan.has(metric)) continue;
        const std::string weight = metric == "wiener" ? "nsr" : "lambda";
        for (const NoiseLevel& level : plan.noise) {
            const SimulatedQuality q =
                simulated_quality(optics.psf, data->scenes, level.model,
                                  static_cast<int>(mask.pattern.pinholes.size()),
                                  mask.pattern.n * mask.pattern.n, decoder, so);
            const std::string& k = level.key;
            row[metric + "_psnr_db_" + k] = finite_or_null(q.mean_psnr_db);
            row[metric + "_ssim_" + k] = finite_or_null(q.mean_ssim);
            row[metric + "_" + weight + "_" + k] = q.weight;
            for (const SceneQuality& s : q.scenes) {
                per_scene[s.scene][metric + "_psnr_db_" + k] = finite_or_null(s.psnr_db);
                per_scene[s.scene][metric + "_ssim_" + k] = finite_or_null(s.ssim);
            }
        }
    }
    if (!per_scene.empty()) row["per_scene"] = per_scene;
    return row;
}

void explain_plan(const ScoreOptions& o, const Plan& plan, Explain& e) {
    const auto skipped = [&](const std::string& m, const std::string& why) {
        e.add(m + ": skipped (" + why + ")");
    };
    if (plan.has("sidelobes")) {
        e.add("sidelobes: torus autocorrelation from the n x n pattern DFT (one small FFT)");
    } else {
        skipped("sidelobes", "not in --metrics");
    }
    if (plan.has("spectrum")) {
        e.add(
            "spectrum: min |P^|, flatness, open fraction, light gain from the pattern DFT; OTF "
            "condition number over the kernel passband |K^| >= 0.1 max |K^|");
    } else {
        skipped("spectrum", "not in --metrics");
    }
    if (plan.has("analytic")) {
        e.add("analytic: closed-form expected Wiener MSE over one period, " + plan.noise_text +
              ", NSR " +
              (plan.nsr.tuned ? std::string("tuned (golden section on log10 NSR)")
                              : join({plan.nsr.value})) +
              ", plus the per-frequency optimal Wiener bound; no simulation");
    } else {
        skipped("analytic", "not in --metrics");
    }
    for (const std::string m : {"wiener", "tv"}) {
        if (plan.has(m)) {
            e.add(m + ": simulated one period (cyclic model: capture = scene (*) PSF, " +
                  plan.noise_text + "), " + std::to_string(plan.scenes.size()) + " scene(s) x " +
                  std::to_string(o.seeds) + " noise seed(s), decoded with " +
                  (m == "wiener"
                       ? "the Wiener filter"
                       : "TV-L2 (ADMM, " + std::to_string(o.tv_iterations) + " iterations max)"));
        } else {
            skipped(m, m == "tv" ? "not in --metrics; add tv to run TV-L2 decodes (slow)"
                                 : "not in --metrics");
        }
    }
    if (!plan.simulated()) skipped("scene rendering", "no simulated metric requested");
    e.add("full-sensor simulation: skipped (the cyclic model needs one period only)");
}

void print_table(const std::vector<nlohmann::ordered_json>& rows, const Plan& plan) {
    std::vector<std::pair<std::string, std::string>> cols;  // (key, header)
    cols.push_back({"holes", "K"});
    if (plan.has("sidelobes")) {
        cols.push_back({"max_sidelobe", "max_sl"});
        cols.push_back({"peak_to_sidelobe_ratio", "PSR"});
    }
    if (plan.has("spectrum")) {
        cols.push_back({"min_abs_pattern_spectrum", "min|P|"});
        cols.push_back({"spectral_flatness", "flat"});
        cols.push_back({"otf_condition_number", "cond"});
    }
    for (const NoiseLevel& level : plan.noise) {
        const std::string& k = level.key;
        if (plan.has("analytic")) cols.push_back({"analytic_wiener_psnr_db_" + k, "A" + k});
        if (plan.has("wiener")) cols.push_back({"wiener_psnr_db_" + k, "W" + k});
        if (plan.has("tv")) cols.push_back({"tv_psnr_db_" + k, "TV" + k});
    }
    std::ostringstream s;
    s << std::left << std::setw(28) << "mask";
    for (const auto& c : cols) s << std::right << std::setw(11) << c.second;
    s << "\n";
    for (const auto& r : rows) {
        std::string name = r["mask"].get<std::string>();
        if (name.size() > 27) name = "..." + name.substr(name.size() - 24);
        s << std::left << std::setw(28) << name;
        for (const auto& c : cols) {
            const auto& v = r[c.first];
            std::ostringstream cell;
            if (v.is_null()) {
                cell << "inf";
            } else if (v.is_number_integer() || v.is_number_unsigned()) {
                cell << v.get<long long>();
            } else {
                cell << std::setprecision(4) << v.get<double>();
            }
            s << std::right << std::setw(11) << cell.str();
        }
        s << "\n";
    }
    s << "PSNR columns in dB over one period: A = analytic Wiener, W = simulated Wiener, TV = "
         "simulated TV-L2; suffix snrS = Gaussian noise at S dB, phP = the photon model at P "
         "electrons "
         "per pinhole. --json for every key.\n";
    std::cout << s.str();
}

nlohmann::ordered_json noise_settings(const Plan& plan) {
    nlohmann::ordered_json levels = nlohmann::ordered_json::array();
    for (const NoiseLevel& level : plan.noise) {
        nlohmann::ordered_json j = noise_json(level.model);
        j["key"] = level.key;
        levels.push_back(j);
    }
    return levels;
}

void run(const ScoreOptions& o, const CLI::App& cmd) {
    const Plan plan = make_plan(o, cmd);
    Explain explain;
    explain_plan(o, plan, explain);
    std::map<int, PeriodData> cache;
    std::vector<nlohmann::ordered_json> rows;
    for (const std::string& path : o.masks)
        rows.push_back(score_mask(path, o, plan, cache, explain));
    if (o.explain) {
        for (const auto& line : explain.lines()) std::cerr << "explain: " << line << "\n";
    }
    if (o.json) {
        nlohmann::ordered_json j;
        j["masks"] = rows;
        j["settings"] = {{"metrics", o.metrics},
                         {"scenes", o.scenes},
                         {"noise", noise_settings(plan)},
                         {"nsr", o.nsr},
                         {"tv_lambda", o.tv_lambda},
                         {"seeds", o.seeds},
                         {"seed", o.seed},
                         {"tv_iterations", o.tv_iterations}};
        if (o.photons.empty()) {  // the Gaussian levels as a plain list, as before --photons
            std::vector<double> snrs;
            for (const NoiseLevel& level : plan.noise) snrs.push_back(level.model.snr_db);
            j["settings"]["snr_db"] = snrs;
        }
        if (o.explain) j["explain"] = explain.lines();
        std::cout << j.dump(2) << "\n";
        return;
    }
    print_table(rows, plan);
}

constexpr const char* kFooter =
    "Metrics (--metrics, comma-separated):\n"
    "  sidelobes  torus autocorrelation of the pattern: peak_autocorrelation (= K), max_sidelobe,\n"
    "             mean_sidelobe, integrated_sidelobe_level (sum of squared sidelobes / peak^2),\n"
    "             peak_to_sidelobe_ratio\n"
    "  spectrum   min_abs_pattern_spectrum (min |P^| over k != 0), spectral_flatness (geometric /\n"
    "             arithmetic mean of |P^|^2 over k != 0; 1 = flat), open_fraction, light_gain "
    "(K),\n"
    "             otf_condition_number (max/min |A^| where |K^| >= 0.1 max |K^|)\n"
    "  analytic   expected Wiener PSNR in closed form over one period, per noise level:\n"
    "             analytic_wiener_psnr_db_snrS (the --nsr filter), analytic_wiener_nsr_snrS,\n"
    "             analytic_optimal_wiener_psnr_db_snrS (per-frequency optimal filter bound).\n"
    "             Prior: the scene files given in --scenes, else 64 natural 1/f textures\n"
    "  wiener     simulated: wiener_psnr_db_snrS, wiener_ssim_snrS, wiener_nsr_snrS (mean over\n"
    "             scenes; per_scene in --json)\n"
    "  tv         simulated TV-L2: tv_psnr_db_snrS, tv_ssim_snrS, tv_lambda_snrS (slow; opt-in)\n"
    "Noise levels: --snr S (keys ...snrS): Gaussian, sigma^2 = mean(capture^2) / 10^(S/10) (the\n"
    "analytic error takes the prior's expected mean(capture^2)); or --photons P (keys ...phP):\n"
    "Poisson shot noise of P K electrons per pixel for a uniform scene of value 1 (K pinholes),\n"
    "plus read noise, dark current, saturation, ADC and film leak from the sensor flags, the\n"
    "expected dark offset removed (see pinmask simulate --help).\n"
    "Simulation: one period, cyclic model, capture = scene (*) PSF + noise; PSNR = 10 log10(1 /\n"
    "MSE) for scenes in [0, 1];\n"
    "SSIM: 11 x 11 Gaussian window (sigma 1.5), valid region. 'tuned' weights minimise the mean\n"
    "MSE over scenes and seeds by golden section on log10 (1e-7..10). Infinite values (a PSR with\n"
    "no sidelobes, a condition number with a spectral zero) are null in --json, inf in the table.\n"
    "Examples: pinmask score a.mask.json b.mask.json --scenes letter-R,usaf,natural --snr 20,30 "
    "--metrics sidelobes,spectrum,analytic,wiener --nsr tuned --json\n"
    "  pinmask score a.mask.json --photons 100,1000 --read-noise 3 --metrics analytic,wiener";

void setup(CLI::App& app) {
    auto o = std::make_shared<ScoreOptions>();
    auto* cmd = app.add_subcommand(
        "score",
        "Score masks: sidelobes, spectrum, analytic and simulated error; one row per mask.");
    cmd->footer(kFooter);
    cmd->add_option("masks", o->masks, "Mask files (*.mask.json)")->required();
    cmd->add_option("--scenes", o->scenes,
                    "Scenes for simulated metrics, comma-separated: letter-R, usaf, "
                    "siemens-star, checker, point, natural, or image files (PNG/TIFF/npy; their "
                    "power spectrum also becomes the analytic prior)")
        ->capture_default_str();
    auto* snr =
        cmd->add_option("--snr", o->snr, "Capture SNRs in dB, comma-separated (Gaussian noise)")
            ->capture_default_str();
    cmd->add_option("--photons", o->photons,
                    "The photon model instead of --snr: mean electrons per pixel through ONE "
                    "pinhole for a uniform scene of value 1, comma-separated levels (K pinholes "
                    "collect K times that: the multiplexing trade-off), with the sensor flags "
                    "below")
        ->excludes(snr);
    add_sensor_flags(*cmd, o->sensor);
    cmd->add_option("--metrics", o->metrics,
                    "Metrics to compute: sidelobes, spectrum, analytic, wiener, tv (see below)")
        ->capture_default_str();
    cmd->add_option("--nsr", o->nsr,
                    "Wiener noise-to-signal ratio (> 0), or 'tuned' (per mask and SNR)")
        ->capture_default_str();
    cmd->add_option("--tv-lambda", o->tv_lambda, "TV-L2 weight (> 0), or 'tuned'")
        ->capture_default_str();
    cmd->add_option("--tv-iters", o->tv_iterations, "TV-L2 maximum ADMM iterations (>= 1)")
        ->capture_default_str();
    cmd->add_option("--seeds", o->seeds,
                    "Noise realisations per scene and SNR for simulated metrics (>= 1); the "
                    "natural scene is always the texture of seed 0")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Base seed of the noise generators")->capture_default_str();
    cmd->add_flag("--allow-violations", o->allow_violations,
                  "Score masks that break their spacing rule even when the file does not "
                  "record that violations were allowed");
    cmd->add_flag("--json", o->json, "Print {masks: [...], settings, explain} as JSON on stdout");
    cmd->add_flag("--explain", o->explain,
                  "List on stderr (and under \"explain\" in --json) what was run, what was "
                  "skipped and why");
    cmd->callback([o, cmd] { run(*o, *cmd); });
}

const Registration kScore(60, "score", setup);

}  // namespace
}  // namespace pinmask::cli
