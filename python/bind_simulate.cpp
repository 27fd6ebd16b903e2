// Scenes and forward simulation (optimize/simulate/scenes.hpp, optimize/simulate/simulate.hpp):
// simulate() follows `pinmask simulate` (cli/cmd_simulate.cpp) minus the file writing.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/units.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/psf.hpp"
#include "io/mask_json.hpp"
#include "optimize/metrics/noise_levels.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"
#include "optimize/simulate/simulate_pipeline.hpp"
#include "python/common.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

SensorSettings sensor_settings(const NoiseArgs& a) {
    SensorSettings f;
    f.read_noise = a.read_noise;
    f.dark_current = a.dark_current;
    f.full_well = a.full_well;
    f.optical_density = a.optical_density;
    f.bits = a.bits;
    return f;
}

NoiseModel noise_model(const NoiseArgs& a) {
    const SensorSettings sensor = sensor_settings(a);
    if (a.photons) {
        if (a.snr_db) {
            std::ostringstream v;
            v << *a.snr_db;
            throw invalid_field(field_ref("snr_db"), v.str(),
                                "cannot be combined with " + field_ref("photons"));
        }
        return photon_model(*a.photons, sensor, nullptr);
    }
    refuse_sensor_settings_without_photons(sensor);
    NoiseModel m;
    const double snr = a.snr_db.value_or(30.0);
    if (std::isinf(snr) && snr > 0) {
        m.kind = NoiseKind::kNone;
        return m;
    }
    m.kind = NoiseKind::kGaussianSnr;
    m.snr_db = snr;
    validate(m);
    return m;
}

Mask mask_arg(const py::handle& obj, bool allow_spacing_violations) {
    if (py::isinstance<Mask>(obj)) return obj.cast<Mask>();
    if (py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__")) {
        io::MaskReadOptions o;
        o.allow_spacing_violations = allow_spacing_violations;
        return io::read_mask_file(py::str(obj).cast<std::string>(), o);
    }
    throw InvalidInput("mask: expected a pinmask.Mask or the path of a *.mask.json");
}

void bind_simulate(py::module_& m) {
    m.def("scene_names", &builtin_scene_names,
          "Built-in scenes: letter-R, usaf, siemens-star, checker, point, natural.");
    m.def(
        "scene",
        [](const std::string& name, int rows, int cols, std::uint64_t seed, double alpha) {
            SceneSpec spec = scene_from_name(name);
            if (rows >= 1 && cols >= 1) {  // make_scene names bad sizes; refuse huge ones first
                // The scene plus its complex spectrum (natural scenes) as the working set.
                check_memory(double(rows) * double(cols) * 3.0 * sizeof(double),
                             "scene " + std::to_string(rows) + " x " + std::to_string(cols));
            }
            spec.seed = seed;
            spec.alpha = alpha;
            Image img;
            {
                py::gil_scoped_release release;
                img = make_scene(spec, rows, cols);
            }
            return image_to_array(std::move(img));
        },
        py::arg("name"), py::arg("rows"), py::arg("cols"), py::arg("seed") = 0,
        py::arg("alpha") = 1.0,
        "A test scene at rows x cols, values in [0, 1]: a built-in name (natural: seed and "
        "amplitude exponent alpha) or an image file (resampled by area). Grey scenes are "
        "(rows, cols) and own the library's buffer.");

    m.def(
        "simulate",
        [](const py::handle& mask_obj, const py::handle& scene_obj, std::optional<double> snr_db,
           std::optional<double> photons, std::optional<double> read_noise,
           std::optional<double> dark_current, std::optional<double> full_well,
           std::optional<int> bits, std::optional<double> optical_density, bool full_sensor,
           std::optional<std::pair<int, int>> sensor, bool dark_frame, std::uint64_t seed,
           bool allow_violations, const std::string& precision, const std::string& geometry,
           const py::object& object_distance, std::optional<std::pair<int, int>> size,
           int threads) {
            // As `simulate --threads` and decode(threads=): 0..1024, 0 all cores.
            if (threads < 0 || threads > 1024)
                throw invalid_field(field_ref("threads"), std::to_string(threads),
                                    "must be 1..1024 (0: all cores)");
            set_fft_threads(
                threads > 0 ? threads
                            : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
            SimulationOptions sim;
            sim.noise = noise_model(
                {snr_db, photons, read_noise, dark_current, full_well, optical_density, bits});
            sim.seed = seed;
            sim.dark_frame = dark_frame;
            sim.precision = parse_precision(precision, field_ref("precision"));
            if (sensor && !full_sensor) {
                throw invalid_field(
                    field_ref("sensor"),
                    std::to_string(sensor->first) + "x" + std::to_string(sensor->second),
                    "only applies with " + field_ref("full_sensor"));
            }
            if (dark_frame && sim.noise.kind != NoiseKind::kPhoton) {
                throw invalid_field(field_ref("dark_frame"), "True",
                                    "needs the photon model (" + field_ref("photons") +
                                        " N): the " + field_ref("snr_db") +
                                        " model has no leak, dark current or read noise to "
                                        "record");
            }
            if (geometry != "integer" && geometry != "exact")
                throw invalid_field(field_ref("geometry"), geometry, "must be integer or exact");
            const Mask mask = mask_arg(mask_obj, allow_violations);
            py::dict out;
            if (geometry == "exact" || !object_distance.is_none() || size) {
                // `simulate --geometry exact` (optimize/simulate/simulate_pipeline, as the command
                // runs it): every pinhole of the tiled mask at its true position for an object at
                // object_distance, over the sensor or a size = (rows, cols) window.
                // object_distance and size need exact geometry (refused here); the pipeline
                // refuses full_sensor and sensor with it, naming them.
                if (geometry != "exact") {
                    throw invalid_field(
                        field_ref(size ? "size" : "object_distance"),
                        size ? std::to_string(size->first) + "x" + std::to_string(size->second)
                             : std::string(py::str(object_distance)),
                        "only used with geometry='exact'");
                }
                SimulatePipelineOptions po;
                po.sim = sim;
                po.exact_geometry = true;
                if (!py::isinstance<py::str>(scene_obj))
                    throw invalid_field(field_ref("scene"), "an array",
                                        "exact geometry renders a named scene or an image file "
                                        "at the sensor window: give its name or path");
                po.scene = scene_from_name(scene_obj.cast<std::string>());
                if (!object_distance.is_none()) {
                    po.object_distance_m = length_value(object_distance, "object_distance", true);
                    check_object_distance(mask.camera, *po.object_distance_m, "object_distance");
                }
                if (size) po.window = Size2{size->first, size->second};  // as typed: ROWSxCOLS
                po.sim.full_sensor = full_sensor;
                if (sensor) po.sensor = Size2{sensor->first, sensor->second};
                SimulatePipelineResult r;
                {
                    py::gil_scoped_release release;
                    r = run_simulate_pipeline(mask, po);
                }
                SimulatedCapture& c = r.capture;
                out["capture"] = image_to_array(std::move(c.capture));
                out["dark"] = c.dark.empty() ? py::object(py::none())
                                             : py::object(image_to_array(std::move(c.dark)));
                out["clean"] = image_to_array(std::move(c.clean));
                out["background"] = c.background;
                out["origin"] = py::make_tuple(c.origin.row, c.origin.col);
                out["whole_period_on_sensor"] = c.whole_period_on_sensor;
                out["psf"] = py::none();  // psf(mask, geometry='exact', ...) gives it
                out["object_distance_m"] = r.summary.object_distance_m;
                return as_result(out);
            }
            SimulatedCapture s;
            Plane psf;
            {
                Image scene;
                const bool named = py::isinstance<py::str>(scene_obj);
                const std::string scene_name_text = named ? scene_obj.cast<std::string>() : "";
                if (!named) scene = image_arg(scene_obj, "scene");
                py::gil_scoped_release release;
                const Kernel kernel = mask_kernel(mask);
                psf = synthesize_psf(mask.pattern, kernel, mask.psf.pixels_per_cell);
                const int mp = static_cast<int>(psf.rows());
                if (named) scene = make_scene(scene_from_name(scene_name_text), mp, mp);
                sim.full_sensor = full_sensor;
                if (full_sensor) {
                    sim.sensor_cols = sensor ? sensor->first : mask.camera.sensor_cols;
                    sim.sensor_rows = sensor ? sensor->second : mask.camera.sensor_rows;
                }
                s = simulate_capture(scene, psf, static_cast<int>(mask.pattern.pinholes.size()),
                                     mask.pattern.n * mask.pattern.n, sim);
            }
            out["capture"] = image_to_array(std::move(s.capture));
            out["dark"] = s.dark.empty() ? py::object(py::none())
                                         : py::object(image_to_array(std::move(s.dark)));
            out["clean"] = image_to_array(std::move(s.clean));
            out["background"] = s.background;
            out["origin"] = py::make_tuple(s.origin.row, s.origin.col);
            out["whole_period_on_sensor"] = s.whole_period_on_sensor;
            out["psf"] = to_array(std::move(psf));
            return as_result(out);
        },
        py::arg("mask"), py::arg("scene") = "letter-R", py::arg("snr_db") = py::none(),
        py::arg("photons") = py::none(), py::arg("read_noise") = py::none(),
        py::arg("dark_current") = py::none(), py::arg("full_well") = py::none(),
        py::arg("bits") = py::none(), py::arg("optical_density") = py::none(),
        py::arg("full_sensor") = false, py::arg("sensor") = py::none(),
        py::arg("dark_frame") = false, py::arg("seed") = 1, py::arg("allow_violations") = false,
        py::arg("precision") = "auto", py::arg("geometry") = "integer",
        py::arg("object_distance") = py::none(), py::arg("size") = py::none(),
        py::arg("threads") = 0,
        "A simulated capture, as `pinmask simulate` computes it: the scene (a name, rendered at "
        "one period, or an array of the period's size, values in [0, 1]) convolved with the "
        "mask's PSF over one period, tiled over the sensor with full_sensor (sensor = (cols, "
        "rows), default the mask's camera), and noise: Gaussian at snr_db dB (default 30; "
        "float('inf') = noiseless) or the photon model (photons = electrons per pinhole for a "
        "uniform scene of 1, read_noise e rms, dark_current e, full_well e, bits of the ADC, "
        "optical_density of the film). dark_frame (photon model only) also draws the frame "
        "through all-opaque film. Units: normalised capture units (noise_model.hpp). precision: "
        "the convolution's, 'auto' (float32 from a 256 x 256 grid) | 'single' | 'double'. Returns "
        "{capture, dark (None unless asked), clean, background (per channel), origin (row, col) "
        "of the period in the frame, whole_period_on_sensor, psf}. geometry 'exact' (as "
        "`simulate --geometry exact`): every pinhole of the tiled mask at its true position for "
        "an object at object_distance (metres or '2m', 'inf'; default the mask's u), over the "
        "sensor or size = (rows, cols) pixels, a named scene; psf is then None "
        "(psf(mask, geometry='exact', ...) gives it) and object_distance_m the u used. threads: "
        "FFTW "
        "threads for transforms of >= 512 x 512 (0: all cores), as `simulate --threads`.");
}

}  // namespace pinmask::python
