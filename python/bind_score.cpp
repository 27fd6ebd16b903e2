// Scoring: score() is `pinmask score` on masks (paths or Mask objects): the command's transaction
// optimize/metrics/score_run (only the metric groups asked for), with score's defaults (scenes
// letter-R, usaf, natural; SNR 20, 30, 40 dB; NSR 0.01; noise seed 0), returned as io/score_json
// renders it for `pinmask score --json`. robust_decoder=True adds
// score --robust-decoder's decoder as arrays (the PSF and the per-frequency NSR map that
// decode(psf=, nsr_map=) reads) instead of files.
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "design/psf/psf.hpp"
#include "io/mask_json.hpp"
#include "io/score_json.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/metrics/score_run.hpp"
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
            ScoreRequest q;
            q.metrics = metric_names(metrics);
            MaskMetricsOptions chosen;
            select_metrics(chosen, q.metrics);
            if (!chosen.depth && (depth_from || depth_to)) {
                throw InvalidInput(field_ref("depth_from_m") + "/" + field_ref("depth_to_m") +
                                   ": add 'depth' to metrics (the range is the depth group's)");
            }
            q.depth_from_m = depth_from.value_or(0.0);
            q.depth_to_m = depth_to.value_or(0.0);
            const SensorSettings sensor{read_noise, dark_current, full_well, optical_density, bits};
            q.noise = noise_levels_arg(snr_db, photons, sensor, ScoreRequest::kDefaultSnrDb,
                                       &q.noise_text);
            q.prior = prior_arg(prior, prior_scenes);
            q.scenes = scenes;
            q.noise_seeds = noise_seeds;
            q.seed = seed;
            q.wiener_nsr = nsr;
            q.tv_lambda = tv_lambda;
            q.tv_iterations = tv_iterations;
            q.robust = robust;
            const MaskMetricsOptions o = q.options();
            if (masks.empty()) throw InvalidInput("masks: give at least one mask");
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
            int index = 0;
            for (const py::handle& h : masks) {
                ++index;
                q.masks.push_back(mask_arg(h, allow_violations));
                q.names.push_back(py::isinstance<Mask>(h) ? "mask " + std::to_string(index)
                                                          : py::str(h).cast<std::string>());
            }
            const Mask first = q.masks.front();  // robust_decoder's one mask
            ScoreReport r;
            {
                py::gil_scoped_release release;
                r = run_score_request(std::move(q));
            }
            std::vector<nlohmann::ordered_json> rows;
            for (const ScoreRow& row : r.rows) rows.push_back(io::score_row_json(row));
            py::dict d = json_value(io::score_json(r, rows, false));  // score --json's dict
            if (robust_decoder) {  // the command writes these arrays as files
                RobustDecoderInputs in;
                {
                    py::gil_scoped_release release;
                    const RobustWienerModel model(first, o.robust,
                                                  r.context->prior(r.rows[0].metrics.period_px),
                                                  o.noise.front().model);
                    in = model.robust_decoder_inputs(pattern_spectrum(first.pattern));
                }
                py::dict rd;
                rd["psf"] = to_array(std::move(in.psf));
                rd["nsr_map"] = to_array(std::move(in.nsr));
                rd["floored"] = in.floored;
                d["masks"].cast<py::list>()[0]["robust_decoder"] = rd;
            }
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
'size=5um,jitter=2um,missing=0.01' (any subset): adds analytic_robust_wiener_psnr_db_<level> and
analytic_robust_wiener_loss_db_<level>. robust_decoder=True (with robust, one mask, one noise
level): adds the row's robust_decoder {psf, nsr_map (arrays; decode(psf=..., nsr_map=...) reads them), floored}
that score --robust-decoder writes as files. allow_violations: score masks that break their
spacing rule. Returns what `pinmask score --json` prints, {masks: [rows], settings} (infinite
figures None), the one transaction optimize/metrics/score_run rendered by io/score_json;
robust_decoder adds its arrays where the command writes files.)");
}

}  // namespace pinmask::python
