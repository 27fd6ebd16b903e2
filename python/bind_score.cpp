// Scoring: score() is `pinmask score` on masks (paths or Mask objects): only the metric groups
// asked for are computed (optimize/metrics/mask_metrics compute_mask_metrics with the selection of
// optimize/metrics/metric_spellings select_metrics), rows built by io/metrics_json as the command
// builds them, with score's defaults (scenes letter-R, usaf, natural; SNR 20, 30, 40 dB; NSR 0.01;
// noise seed 0), and the rows carry the keys of `pinmask score --json`. robust_decoder=True adds
// score --robust-decoder's decoder as arrays (the PSF and the per-frequency NSR map that
// decode(psf=, nsr_map=) reads) instead of files.
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "design/psf/psf.hpp"
#include "io/mask_json.hpp"
#include "io/metrics_json.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/level_args.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

// metrics= as a list of names or one comma-separated string (as --metrics).
std::vector<std::string> metric_names(const py::handle& metrics) {
    if (py::isinstance<py::str>(metrics)) {
        std::vector<std::string> names;
        const std::string text = metrics.cast<std::string>();
        std::size_t start = 0;
        while (true) {
            const std::size_t comma = text.find(',', start);
            names.push_back(text.substr(start, comma - start));
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
        return names;
    }
    return metrics.cast<std::vector<std::string>>();
}

}  // namespace

void bind_score(py::module_& m) {
    m.def(
        "score",
        [](const py::list& masks, const py::handle& metrics, const std::vector<std::string>& scenes,
           const py::object& snr_db, const py::object& photons, std::optional<double> read_noise,
           std::optional<double> dark_current, std::optional<double> full_well,
           std::optional<int> bits, std::optional<double> optical_density, const py::object& prior,
           int prior_scenes, const std::string& nsr, const std::string& tv_lambda,
           int tv_iterations, int noise_seeds, std::uint64_t seed,
           const std::optional<std::string>& robust, bool robust_decoder, bool allow_violations,
           std::optional<double> depth_from, std::optional<double> depth_to) {
            MaskMetricsOptions o;
            select_metrics(o, metric_names(metrics));
            if (!o.depth && (depth_from || depth_to)) {
                throw InvalidInput(field_ref("depth_from_m") + "/" + field_ref("depth_to_m") +
                                   ": add 'depth' to metrics (the range is the depth group's)");
            }
            o.depth_range.from_m = depth_from.value_or(0.0);
            o.depth_range.to_m = depth_to.value_or(0.0);
            const SensorSettings sensor{read_noise, dark_current, full_well, optical_density, bits};
            o.noise = noise_levels_arg(snr_db, photons, sensor, {20.0, 30.0, 40.0});
            o.prior = prior_arg(prior, prior_scenes);
            o.scenes = scene_specs_from_names(scenes);
            o.simulation.noise_seeds = noise_seeds;
            o.simulation.seed = seed;
            set_decoder_settings(o.simulation, nsr, tv_lambda, tv_iterations);
            if (robust) o.robust = parse_fabrication_errors(*robust);
            o.validate();
            if (masks.empty()) throw InvalidInput(field_ref("masks") + ": give at least one mask");
            if (robust_decoder) {
                if (!o.robust.any())
                    throw InvalidInput(field_ref("robust_decoder") + " needs " +
                                       field_ref("robust") + " (the fabrication errors)");
                if (masks.size() != 1)
                    throw invalid_field(field_ref("robust_decoder"), "True",
                                        "needs exactly one mask (the decoder is the mask's), got " +
                                            std::to_string(masks.size()));
                if (o.noise.size() != 1)
                    throw invalid_field(field_ref("robust_decoder"), "True",
                                        "needs one noise level (the filter depends on it), got " +
                                            std::to_string(o.noise.size()));
            }
            std::vector<Mask> loaded;
            std::vector<std::string> names;
            int index = 0;
            for (const py::handle& h : masks) {
                ++index;
                loaded.push_back(mask_arg(h, allow_violations));
                names.push_back(py::isinstance<Mask>(h) ? "mask " + std::to_string(index)
                                                        : py::str(h).cast<std::string>());
            }
            MetricsContext context(o);
            py::list rows;
            for (std::size_t i = 0; i < loaded.size(); ++i) {
                MaskMetrics mm;
                {
                    py::gil_scoped_release release;
                    mm = compute_mask_metrics(loaded[i], context);
                }
                nlohmann::ordered_json row_json, per_scene = nlohmann::ordered_json::object();
                row_json["mask"] = names[i];
                row_json["geometry_hash"] = geometry_hash(loaded[i]);
                row_json["n"] = mm.n;
                row_json["holes"] = mm.holes;
                row_json["pixels_per_cell"] = mm.pixels_per_cell;
                row_json["period_px"] = mm.period_px;
                io::metrics_json(mm, row_json, &per_scene);  // score --json's keys and values
                if (!per_scene.empty()) row_json["per_scene"] = per_scene;
                py::dict row = json_value(row_json);
                if (robust_decoder) {
                    RobustDecoderInputs in;
                    {
                        py::gil_scoped_release release;
                        const RobustWienerModel model(loaded[i], o.robust,
                                                      context.prior(mm.period_px),
                                                      o.noise.front().model);
                        in = model.robust_decoder_inputs(pattern_spectrum(loaded[i].pattern));
                    }
                    py::dict rd;
                    rd["psf"] = to_array(std::move(in.psf));
                    rd["nsr_map"] = to_array(std::move(in.nsr));
                    rd["floored"] = in.floored;
                    row["robust_decoder"] = rd;
                }
                rows.append(row);
            }
            py::list levels;
            for (const NoiseLevel& level : o.noise) levels.append(py::str(level.key));
            py::dict settings;
            py::list chosen;
            for (const std::string& n : metric_names(metrics)) chosen.append(n);
            settings["metrics"] = chosen;
            settings["scenes"] = scenes;
            settings["noise"] = levels;
            settings["prior"] = o.prior.description();
            settings["nsr"] = nsr;
            settings["tv_lambda"] = tv_lambda;
            settings["seeds"] = noise_seeds;
            settings["seed"] = seed;
            settings["tv_iterations"] = tv_iterations;
            settings["robust"] = o.robust.description();
            if (o.depth) {
                settings["depth_from_m"] = o.depth_range.from_m;  // 0: working distance / 2
                settings["depth_to_m"] = o.depth_range.to_m;      // 0: twice the working distance
            }
            py::dict d;
            d["masks"] = rows;
            d["settings"] = settings;
            return as_result(d);
        },
        py::arg("masks"), py::arg("metrics") = "sidelobes,spectrum,analytic,wiener",
        py::arg("scenes") = std::vector<std::string>{"letter-R", "usaf", "natural"},
        py::arg("snr_db") = py::none(), py::arg("photons") = py::none(),
        py::arg("read_noise") = py::none(), py::arg("dark_current") = py::none(),
        py::arg("full_well") = py::none(), py::arg("bits") = py::none(),
        py::arg("optical_density") = py::none(), py::arg("prior") = "natural",
        py::arg("prior_scenes") = 16, py::arg("nsr") = "0.01", py::arg("tv_lambda") = "1e-3",
        py::arg("tv_iterations") = 200, py::arg("noise_seeds") = 1, py::arg("seed") = 0,
        py::arg("robust") = py::none(), py::arg("robust_decoder") = false,
        py::arg("allow_violations") = false, py::arg("depth_from") = py::none(),
        py::arg("depth_to") = py::none(),
        R"(Scores masks as `pinmask score` does: one row per mask with the keys of its --json, only
the metric groups asked for computed, score's defaults and numbers.

masks: a list of Mask objects or *.mask.json paths. metrics: 'sidelobes', 'spectrum',
'analytic', 'wiener', 'tv', 'depth' (a list or one comma-separated string; tv is slow; depth
needs photons). depth: the Cramer-Rao bound on a point source's distance over depth_from ..
depth_to metres (None, None: the working distance / 2 .. x 2), 3 distances equally spaced in
1/u: depth_crb_rel_<level> (worst sigma_u / u), depth_axial_fwhm_m_<level> (worst 2.355 sigma_u,
metres), depth_worst_distance_m_<level>, depth_from_m, depth_to_m. scenes: the
simulated scenes (built-in names or image files). Noise: snr_db (Gaussian, dB; a number or a
list; None: 20, 30, 40) or photons (electrons per pixel through one pinhole; a number or a list)
with read_noise (rms electrons), dark_current (mean electrons per pixel), full_well (electrons),
bits (ADC, needs full_well), optical_density (film OD). prior, prior_scenes: the analytic
error's scene prior. nsr, tv_lambda: the simulated decoders' weights (a number > 0 or 'tuned');
tv_iterations: TV-L2 iterations. noise_seeds: noise realisations per scene and level (1..1000;
score --seeds); seed: the base seed of the noise. robust: fabrication errors
'size=5um,jitter=2um,missing=0.01' (any subset): adds robust_wiener_psnr_db_<level> and
robust_loss_db_<level>. robust_decoder=True (with robust, one mask, one noise level): adds the
row's robust_decoder {psf, nsr_map (arrays; decode(psf=..., nsr_map=...) reads them), floored}
that score --robust-decoder writes as files. allow_violations: score masks that break their
spacing rule. Returns {masks: [rows], settings}; infinite figures are None (null in --json).)");
}

}  // namespace pinmask::python
