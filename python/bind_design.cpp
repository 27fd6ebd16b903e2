// Camera and optics numbers (design/camera.hpp, design/optics.hpp, design/kernel_model.hpp).
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/field_names.hpp"
#include "core/units.hpp"
#include "design/camera.hpp"
#include "design/kernel_model.hpp"
#include "design/kernel_validity.hpp"
#include "design/optics.hpp"
#include "design/working_distance.hpp"
#include "io/camera_json.hpp"
#include "python/common.hpp"
#include "python/keyword_names.hpp"
#include "python/values.hpp"

namespace pinmask::python {

double length_value(const py::handle& v, const std::string& field, bool allow_inf) {
    if (py::isinstance<py::str>(v)) {
        return parse_length_m(v.cast<std::string>(), field,
                              allow_inf ? AllowInfinity::kYes : AllowInfinity::kNo);
    }
    const double x = v.cast<double>();
    if (std::isnan(x) || (std::isinf(x) && !(allow_inf && x > 0)))
        throw invalid_field(field, py::str(v).cast<std::string>(),
                            allow_inf ? "must be finite or +inf" : "must be finite");
    return x;
}

py::dict optics_dict(const OpticsReport& r, const WorkingDistance& wd,
                     const std::vector<std::string>& kernel_warnings) {
    py::dict d;
    d["camera"] = r.camera;
    d["geometry"] =
        py::dict(py::arg("n") = r.geometry.n, py::arg("holes") = r.geometry.holes,
                 py::arg("tiles") = py::make_tuple(r.geometry.tiles_rows, r.geometry.tiles_cols));
    // Keys as `pinmask design --json` (cli/outputs/design_report): plain and "_at_u" keys at
    // the working distance u, "_at_inf" keys for a distant object.
    d["optimum_pinhole_m"] = r.optimum_pinhole_m;
    d["fresnel_number"] = r.fresnel_number;
    d["fresnel_number_with_lens"] = r.fresnel_number_with_lens_at_u;
    d["fresnel_number_with_lens_at_u"] = r.fresnel_number_with_lens_at_u;
    d["fresnel_number_with_lens_at_inf"] = r.fresnel_number_with_lens;
    d["effective_distance_m"] = r.effective_distance_at_u_m;
    d["effective_distance_at_u_m"] = r.effective_distance_at_u_m;
    d["effective_distance_at_inf_m"] = r.effective_distance_m;
    d["magnification"] = r.magnification_at_u;
    d["magnification_at_u"] = r.magnification_at_u;
    d["magnification_at_inf"] = r.magnification;
    d["geometric_spot_m"] = r.geometric_spot_at_u_m;
    d["geometric_spot_at_u_m"] = r.geometric_spot_at_u_m;
    d["geometric_spot_at_inf_m"] = r.geometric_spot_m;
    d["pixels_per_cell"] = r.pixels_per_cell_at_u;
    d["pixels_per_cell_at_u"] = r.pixels_per_cell_at_u;
    d["pixels_per_cell_at_inf"] = r.pixels_per_cell;
    d["integer_pixels_per_cell"] = wd.pixels_per_cell;
    d["integer_pixels_per_cell_at_inf"] = r.integer_pixels_per_cell;
    d["pinhole_for_integer_pixels_m"] = wd.pinhole_for_pixels_per_cell_m;
    d["pinhole_for_integer_pixels_at_inf_m"] = r.pinhole_for_integer_pixels_m;
    d["max_separation_m"] = r.max_separation_m;
    d["lsi_tolerance_px"] = r.options.lsi_tolerance_px;
    d["lsi_mismatch_px"] = wd.lsi_mismatch_px;
    d["lsi_shift_invariant"] = wd.is_shift_invariant();
    d["lsi_mismatch_at_inf_px"] = r.lsi_mismatch_px;
    d["lsi_min_object_distance_at_inf_m"] = r.lsi_min_object_distance_m;
    d["psf_size_px"] = wd.psf_size_px;
    d["psf_size_at_inf_px"] = r.psf_size_px;
    d["periods_on_sensor"] = py::dict(py::arg("cols") = wd.periods_on_sensor_cols,
                                      py::arg("rows") = wd.periods_on_sensor_rows);
    d["periods_on_sensor_at_inf"] = py::dict(py::arg("cols") = r.periods_on_sensor_cols,
                                             py::arg("rows") = r.periods_on_sensor_rows);
    d["mask_size_m"] =
        py::dict(py::arg("width") = r.mask_width_m, py::arg("height") = r.mask_height_m);
    d["open_fraction"] = r.open_fraction;
    d["light_gain"] = r.light_gain;
    d["kernel_model"] = kernel_model_name(r.kernel_model);
    d["kernel_reason"] = r.kernel_reason;
    // The working distance (design/working_distance.hpp), under design --json's keys.
    d["whole_pixels_per_cell_at_u"] = wd.pixels_per_cell;
    d["pinhole_for_pixels_per_cell_m"] = wd.pinhole_for_pixels_per_cell_m;
    d["period_at_u_px"] = wd.period_px;
    d["lsi_mismatch_at_u_px"] = wd.lsi_mismatch_px;
    d["object_distance_range_m"] = py::make_tuple(wd.range_near_m, wd.range_far_m);
    d["optimum_pinhole_lensless_m"] = wd.optimum_pinhole_lensless_m;
    d["optimum_pinhole_with_lens_m"] = wd.optimum_pinhole_with_lens_m;
    d["spot_spread_cells"] = wd.spot_spread_cells;
    d["spot_spreads_beyond_cell"] = wd.spreads_beyond_cell();
    d["kernel_warnings"] = kernel_warnings;
    return d;
}

void bind_design(py::module_& m) {
    py::class_<Camera>(m, "Camera",
                       "The coded-pinhole-lens camera; lengths in metres (a float) or a string "
                       "with a unit ('440um', '55mm', '6m'; object_distance_m and lens_focal_m "
                       "also 'inf'). Defaults: the paper's prototype.")
        .def(py::init([](const py::object& object_distance_m, const py::object& lens_focal_m,
                         const py::object& sensor_distance_m, const py::object& wavelength_m,
                         const py::object& pixel_pitch_m, const py::object& pinhole_m,
                         int sensor_cols, int sensor_rows) {
                 Camera c;
                 c.object_distance_m = length_value(object_distance_m, "object_distance_m", true);
                 c.lens_focal_m = length_value(lens_focal_m, "lens_focal_m", true);
                 c.sensor_distance_m = length_value(sensor_distance_m, "sensor_distance_m", false);
                 c.wavelength_m = length_value(wavelength_m, "wavelength_m", false);
                 c.pixel_pitch_m = length_value(pixel_pitch_m, "pixel_pitch_m", false);
                 c.pinhole_m = length_value(pinhole_m, "pinhole_m", false);
                 c.sensor_cols = sensor_cols;
                 c.sensor_rows = sensor_rows;
                 validate(c);
                 return c;
             }),
             py::arg("object_distance_m") = 6.0, py::arg("lens_focal_m") = 0.120,
             py::arg("sensor_distance_m") = 0.055, py::arg("wavelength_m") = 550e-9,
             py::arg("pixel_pitch_m") = 30e-6, py::arg("pinhole_m") = 440e-6,
             py::arg("sensor_cols") = 720, py::arg("sensor_rows") = 480)
        .def_readwrite("object_distance_m", &Camera::object_distance_m,
                       "u: object distance, m (+inf: distant object)")
        .def_readwrite("lens_focal_m", &Camera::lens_focal_m,
                       "f': lens focal length, m (+inf: no lens)")
        .def_readwrite("sensor_distance_m", &Camera::sensor_distance_m,
                       "f: lens-to-sensor distance, m")
        .def_readwrite("wavelength_m", &Camera::wavelength_m, "design wavelength, m")
        .def_readwrite("pixel_pitch_m", &Camera::pixel_pitch_m, "w: sensor pixel pitch, m")
        .def_readwrite("pinhole_m", &Camera::pinhole_m, "d: pinhole side = cell side, m")
        .def_readwrite("sensor_cols", &Camera::sensor_cols, "sensor width, pixels")
        .def_readwrite("sensor_rows", &Camera::sensor_rows, "sensor height, pixels")
        .def(
            "validate", [](const Camera& c) { validate(c); },
            "ValueError naming the first field that is not physical.")
        .def("to_json", &io::camera_file_text,
             "The text of the camera file save_camera writes (and `pinmask design "
             "--save-camera`), lengths in metres.")
        .def(
            "__eq__",
            [](const Camera& a, const Camera& b) {
                return a.object_distance_m == b.object_distance_m &&
                       a.lens_focal_m == b.lens_focal_m &&
                       a.sensor_distance_m == b.sensor_distance_m &&
                       a.wavelength_m == b.wavelength_m && a.pixel_pitch_m == b.pixel_pitch_m &&
                       a.pinhole_m == b.pinhole_m && a.sensor_cols == b.sensor_cols &&
                       a.sensor_rows == b.sensor_rows;
            },
            py::arg("other"))
        .def("__repr__", [](const Camera& c) {
            // Python's own float repr (the shortest that reads back the same value): 850 nm
            // prints as 8.5e-07, where std::to_string's six decimals would print 0.000001.
            const auto r = [](double v) { return std::string(py::repr(py::float_(v))); };
            return "Camera(object_distance_m=" + r(c.object_distance_m) +
                   ", lens_focal_m=" + r(c.lens_focal_m) +
                   ", sensor_distance_m=" + r(c.sensor_distance_m) +
                   ", wavelength_m=" + r(c.wavelength_m) + ", pixel_pitch_m=" + r(c.pixel_pitch_m) +
                   ", pinhole_m=" + r(c.pinhole_m) +
                   ", sensor_cols=" + std::to_string(c.sensor_cols) +
                   ", sensor_rows=" + std::to_string(c.sensor_rows) + ")";
        });

    m.def(
        "load_camera", [](const std::filesystem::path& path) { return io::read_camera_file(path); },
        py::arg("path"),
        "Reads and validates a *.camera.json (the file `pinmask design --save-camera` writes and "
        "--camera reads; ValueError naming the file, the key and the rule).");
    m.def(
        "save_camera",
        [](const Camera& camera, const std::filesystem::path& path) {
            io::write_camera_file(path, camera);
        },
        py::arg("camera"), py::arg("path"),
        "Writes a *.camera.json atomically (the bytes of `pinmask design --save-camera` for the "
        "same camera; every command's --camera reads it).");

    m.def("paper_camera", &paper_camera,
          "The paper's prototype: u = 6 m, f' = 120 mm, f = 55 mm, d = 440 um, w = 30 um, "
          "720 x 480 pixels, lambda = 550 nm.");

    m.def(
        "optics",
        [](const std::optional<Camera>& camera, int grid, int holes, int tiles,
           const std::string& kernel, double lsi_tolerance_px) {
            PatternGeometry g{grid, holes, tiles, tiles};
            OpticsOptions o;
            o.lsi_tolerance_px = lsi_tolerance_px;
            const Camera c = camera.value_or(paper_camera());
            const KernelModel model = parse_kernel_model(kernel, field_ref("kernel"));
            if (!(lsi_tolerance_px > 0) || !std::isfinite(lsi_tolerance_px)) {
                throw invalid_field(field_ref("lsi_tolerance_px"), std::to_string(lsi_tolerance_px),
                                    "must be finite and > 0 (0 or less gives an empty "
                                    "object-distance range)");
            }
            check_object_distance(c, c.object_distance_m, "object_distance_m");
            OpticsReport r = compute_optics(c, g, model, o);
            // As `pinmask design`: a kernel model outside its validity says so in the reason.
            KernelValidity validity = kernel_validity(c, r.kernel_model);
            for (auto& w : validity.warnings) w = py_names::spell_keywords(w);
            if (!validity.model_accurate)
                r.kernel_reason = "NOT accurate: " + validity.warnings.front();
            const WorkingDistance wd = compute_working_distance(c, g, {lsi_tolerance_px, 0});
            return optics_dict(r, wd, validity.warnings);
        },
        py::arg("camera") = py::none(), py::arg("grid") = 16, py::arg("holes") = 20,
        py::arg("tiles") = 2, py::arg("kernel") = "auto", py::arg("lsi_tolerance_px") = 1.0,
        "The optics report of `pinmask design --json` as a dict (same keys and numbers; lengths "
        "in metres with _m suffixes, infinite values as float('inf') where the CLI writes null "
        "and a note; keys without a suffix and \"_at_u\" keys are at the working distance u, "
        "\"_at_inf\" keys are the distant-object design values), the working distance "
        "included: whole_pixels_per_cell_at_u, "
        "pinhole_for_pixels_per_cell_m, period_at_u_px, lsi_mismatch_at_u_px, "
        "object_distance_range_m (near, far; far inf when shift invariant to infinity), "
        "optimum_pinhole_lensless_m, optimum_pinhole_with_lens_m, spot_spread_cells (cells), "
        "spot_spreads_beyond_cell, kernel_warnings. grid n (cells per side), holes K, tiles per "
        "side, kernel (kernel_models()), lsi_tolerance_px in pixels.");

    m.def(
        "kernel_models", [] { return name_list(kKernelModelNames); },
        "Names of the single-pinhole kernel models.");
    m.def(
        "choose_kernel_model",
        [](double fresnel_number) {
            const KernelChoice c = choose_kernel_model(fresnel_number);
            return py::make_tuple(kernel_model_name(c.model), c.reason);
        },
        py::arg("fresnel_number"),
        "The (model, reason) 'auto' picks for a Fresnel number N (dimensionless).");
}

}  // namespace pinmask::python
