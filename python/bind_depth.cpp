// depth(): `pinmask depth`'s library pipeline (optimize/metrics/depth_loss depth_analysis) from
// Python, one dict per distance: io/depth_json's rendering, what `depth --json` prints. Noise as
// metrics(): snr_db (one level; inf: noiseless) or photons with the sensor stages; the Wiener NSR
// tuned as score tunes it unless nsr gives a value.
#include <cmath>
#include <limits>
#include <optional>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "io/depth_json.hpp"
#include "optimize/metrics/depth_loss.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/level_args.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {
namespace {

// The one noise level: None for a noiseless run (snr_db = inf), else noise_levels_arg's.
NoiseModel depth_noise(const py::object& snr_db, const py::object& photons,
                       const SensorSettings& sensor) {
    if (photons.is_none() && py::isinstance<py::float_>(snr_db) &&
        std::isinf(snr_db.cast<double>()) && snr_db.cast<double>() > 0) {
        refuse_sensor_settings_without_photons(sensor);
        NoiseModel none;
        none.kind = NoiseKind::kNone;
        return none;
    }
    const std::vector<NoiseLevel> levels = noise_levels_arg(snr_db, photons, sensor, {30.0});
    if (levels.size() != 1) {
        throw invalid_field(field_ref(photons.is_none() ? "snr_db" : "photons"),
                            std::to_string(levels.size()) + " levels", "depth takes one level");
    }
    return levels.front().model;
}

}  // namespace

void bind_depth(py::module_& m) {
    m.def(
        "depth",
        [](const py::handle& mask, const std::optional<std::vector<double>>& distances,
           std::optional<double> from_m, std::optional<double> to_m, std::optional<int> steps,
           const py::object& snr_db, const py::object& photons, std::optional<double> read_noise,
           std::optional<double> dark_current, std::optional<double> full_well,
           std::optional<int> bits, std::optional<double> optical_density, const std::string& nsr,
           const std::vector<std::string>& scenes, bool tv, std::uint64_t seed) {
            const SensorSettings sensor{read_noise, dark_current, full_well, optical_density, bits};
            DepthOptions d;
            d.noise = depth_noise(snr_db, photons, sensor);
            d.wiener_nsr = parse_weight_choice(nsr, field_ref("wiener_nsr"));
            d.scenes = scenes;
            d.with_tv = tv;
            d.seed = seed;
            d.threads = fft_threads();
            std::vector<double> us;
            // steps is read with a range only: beside distances it was ignored without a word.
            if (distances && (from_m || to_m || steps))
                throw invalid_field(field_ref("distances"), "given",
                                    "give either it or from_m/to_m/steps");
            if (distances) {
                us = *distances;
            } else {
                if (!from_m || !to_m)
                    throw InvalidInput(
                        "depth needs distances=[...], or from_m and to_m (and steps)");
                us = depth_range(*from_m, *to_m, steps.value_or(8));
            }
            const Mask mk = mask_arg(mask);
            std::vector<DepthRecord> records;
            {
                py::gil_scoped_release release;
                records = depth_analysis(mk, us, d);
            }
            const py::list out = json_value(io::depth_json(records));  // depth --json
            return as_result(out);
        },
        py::arg("mask"), py::arg("distances") = py::none(), py::arg("from_m") = py::none(),
        py::arg("to_m") = py::none(), py::arg("steps") = py::none(), py::arg("snr_db") = py::none(),
        py::arg("photons") = py::none(), py::arg("read_noise") = py::none(),
        py::arg("dark_current") = py::none(), py::arg("full_well") = py::none(),
        py::arg("bits") = py::none(), py::arg("optical_density") = py::none(),
        py::arg("nsr") = "tuned",
        py::arg("scenes") = std::vector<std::string>{"letter-R", "natural"}, py::arg("tv") = true,
        py::arg("seed") = 1,
        R"(Depth analysis of a mask (Mask or *.mask.json path) as `pinmask depth`: per object
distance u (metres; inf allowed), the pitch (pixels_per_cell), period_px, lsi_mismatch_px and the
PSNR lost (dB) when the capture recorded at u (exact geometry) is decoded with the mask's integer
PSF, Wiener and TV (tv=False: Wiener only, tv_psnr_loss_db None). distances=[...] or from_m, to_m
(inf allowed) and steps (points equally spaced in 1/u; None: 8; refused beside distances, as
--steps beside --distances). Noise: snr_db (one level, dB; default 30;
inf: none) or photons (electrons per pixel through one pinhole) with read_noise, dark_current,
full_well, bits, optical_density. nsr: 'tuned' (once per run, as metrics(nsr='tuned')) or a
number. Returns a list of dicts with the keys of `pinmask depth --json`.)");
}

}  // namespace pinmask::python
