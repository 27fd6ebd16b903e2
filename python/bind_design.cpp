// Camera and optics numbers (design/optics/camera.hpp, design/optics/optics.hpp,
// design/psf/kernel_model.hpp).
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "design/optics/camera.hpp"
#include "design/optics/default_pinhole.hpp"
#include "design/optics/design_run.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/optics/image_plane.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/spectrum.hpp"
#include "design/optics/working_distance.hpp"
#include "design/pattern/packing_bound.hpp"
#include "design/psf/design_kernel.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/kernel_model.hpp"
#include "design/psf/kernel_validity.hpp"
#include "export/pipeline/vendor_presets.hpp"
#include "io/camera_json.hpp"
#include "io/design_json.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/keyword_names.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

double length_value(const py::handle& v, const std::string& field, bool allow_inf) {
    if (py::isinstance<py::str>(v)) {
        return parse_length_m(v.cast<std::string>(), field,
                              allow_inf ? AllowInfinity::kYes : AllowInfinity::kNo);
    }
    if (py::isinstance<py::bool_>(v) ||
        !(py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v) ||
          PyNumber_Check(v.ptr()) == 1)) {
        throw py::type_error(py_names::spell_keywords(
            field +
            ": a length is a number of metres or a string with a unit such as '440um', "
            "not a value of type " +
            py::str(py::type::of(v).attr("__name__")).cast<std::string>()));
    }
    const double x = py::reinterpret_borrow<py::object>(v).cast<double>();
    if (std::isnan(x) || (std::isinf(x) && !(allow_inf && x > 0)))
        throw invalid_field(field, py::str(v).cast<std::string>(),
                            allow_inf ? "must be finite or +inf" : "must be finite");
    return x;
}

// optics()'s spelling of a field in its kernel warnings: as every function, except a keyword
// optics() lacks, which names the functions that take it (as design's flags,
// cli/options/flag_names).
std::optional<std::string> optics_keyword(std::string_view field) {
    if (field == "energy_fraction")
        return "energy_fraction (a keyword of kernel(), psf() and write_psf(), not of optics())";
    return py_names::keyword_spelling(field);
}

void bind_design(py::module_& m) {
    py::class_<Camera>(m, "Camera",
                       "The coded-pinhole-lens camera; lengths in metres (a float) or a string "
                       "with a unit ('440um', '55mm', '6m'; object_distance_m and lens_focal_m "
                       "also 'inf'). Defaults (None): the paper's prototype; with other optics "
                       "(lens_focal_m, sensor_distance_m, wavelength_m or pixel_pitch_m given) "
                       "and no pinhole_m, the pinhole for whole pixels per cell nearest the "
                       "diffraction optimum, with a UserWarning (as the command line without "
                       "--pinhole). A length above its quantity's range (pinhole over 10 mm, "
                       "pixel over 1 mm, wavelength over 100 um, ...) is a ValueError naming the "
                       "unit it probably meant.")
        .def(py::init([](const py::object& object_distance_m, const py::object& lens_focal_m,
                         const py::object& sensor_distance_m, const py::object& wavelength_m,
                         const py::object& pixel_pitch_m, const py::object& pinhole_m,
                         int sensor_cols, int sensor_rows, const py::object& bandwidth_m) {
                 // None: the paper's value. Other optics than the paper's without pinhole_m get
                 // the whole-pixel pinhole nearest the diffraction optimum, as the command
                 // line does without --pinhole (design/optics/default_pinhole), with a UserWarning.
                 Camera c;
                 const auto set = [](double& to, const py::object& v, const char* field,
                                     bool allow_inf) {
                     if (!v.is_none()) to = length_value(v, field, allow_inf);
                 };
                 set(c.object_distance_m, object_distance_m, "object_distance_m", true);
                 set(c.lens_focal_m, lens_focal_m, "lens_focal_m", true);
                 set(c.sensor_distance_m, sensor_distance_m, "sensor_distance_m", false);
                 set(c.wavelength_m, wavelength_m, "wavelength_m", false);
                 set(c.pixel_pitch_m, pixel_pitch_m, "pixel_pitch_m", false);
                 set(c.pinhole_m, pinhole_m, "pinhole_m", false);
                 c.sensor_cols = sensor_cols;
                 c.sensor_rows = sensor_rows;
                 c.bandwidth_m = length_value(bandwidth_m, "bandwidth_m", false);
                 validate(c);
                 const bool other_optics = !lens_focal_m.is_none() ||
                                           !sensor_distance_m.is_none() ||
                                           !wavelength_m.is_none() || !pixel_pitch_m.is_none();
                 if (pinhole_m.is_none() && other_optics) {
                     const DefaultPinhole chosen = default_pinhole(c);
                     c.pinhole_m = chosen.pinhole_m;
                     validate(c);
                     if (PyErr_WarnEx(PyExc_UserWarning,
                                      ("pinmask: " + py_names::spell_keywords(chosen.note)).c_str(),
                                      1) < 0)
                         throw py::error_already_set();
                 }
                 return c;
             }),
             py::arg("object_distance_m") = 6.0, py::arg("lens_focal_m") = py::none(),
             py::arg("sensor_distance_m") = py::none(), py::arg("wavelength_m") = py::none(),
             py::arg("pixel_pitch_m") = py::none(), py::arg("pinhole_m") = py::none(),
             py::arg("sensor_cols") = 720, py::arg("sensor_rows") = 480,
             py::arg("bandwidth_m") = 0.0)
        .def_readwrite("object_distance_m", &Camera::object_distance_m,
                       "u: object distance, m (+inf: distant object)")
        .def_readwrite("lens_focal_m", &Camera::lens_focal_m,
                       "f': lens focal length, m (+inf: no lens)")
        .def_readwrite("sensor_distance_m", &Camera::sensor_distance_m,
                       "f: lens-to-sensor distance, m")
        .def_readwrite("wavelength_m", &Camera::wavelength_m,
                       "design wavelength (the centre of the band), m")
        .def_readwrite("bandwidth_m", &Camera::bandwidth_m,
                       "B: full width at half maximum of the light's spectrum, m (0: one "
                       "wavelength; kernels sum a Gaussian band at 13 wavelengths over +-1.5 FWHM)")
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
                       a.wavelength_m == b.wavelength_m && a.bandwidth_m == b.bandwidth_m &&
                       a.pixel_pitch_m == b.pixel_pitch_m && a.pinhole_m == b.pinhole_m &&
                       a.sensor_cols == b.sensor_cols && a.sensor_rows == b.sensor_rows;
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
                   ", sensor_rows=" + std::to_string(c.sensor_rows) +
                   ", bandwidth_m=" + r(c.bandwidth_m) + ")";
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
           const std::string& kernel, double lsi_tolerance_px,
           std::optional<long long> pixels_per_cell, const std::optional<std::string>& solve,
           const py::object& fab_grid, const std::optional<std::string>& vendor, double spacing,
           const std::optional<std::filesystem::path>& save_camera) {
            PatternGeometry g{grid, holes, tiles, tiles};
            if (!std::isfinite(spacing) || spacing < 0)
                throw invalid_field(field_ref("spacing"), std::to_string(spacing),
                                    "must be finite and >= 0");
            Camera c = camera.value_or(paper_camera());
            const KernelModel model = parse_kernel_model(kernel, field_ref("kernel"));
            validate_lsi_tolerance(lsi_tolerance_px);  // the command line's range
            // Solving the pinhole, as `pinmask design --solve pinhole / --pixels-per-cell N`
            // (the same checks in the same order, the same library calls).
            if (solve && *solve != "pinhole")
                throw invalid_field(field_ref("solve"), *solve, "must be 'pinhole'");
            if (pixels_per_cell && (*pixels_per_cell < 1 || *pixels_per_cell > kMaxPixelsPerCell))
                throw invalid_field(field_ref("pixels_per_cell"), std::to_string(*pixels_per_cell),
                                    "must be between 1 and " + std::to_string(kMaxPixelsPerCell));
            check_object_distance(c, c.object_distance_m, "object_distance_m");
            if (save_camera) {  // as --save-camera: into an existing folder
                const std::filesystem::path dir = save_camera->parent_path();
                if (!dir.empty() && !std::filesystem::is_directory(dir))
                    throw invalid_field(field_ref("save_camera"), save_camera->string(),
                                        "its folder does not exist");
            }
            // The command's transaction (design/optics/design_run): the solve, the report, the
            // kernel psf would build and the packing bound.
            DesignRequest q;
            q.camera = c;
            q.geometry = g;
            q.spacing_cells = spacing;
            q.model = model;
            q.kernel = kernel;
            q.lsi_tolerance_px = lsi_tolerance_px;
            if (pixels_per_cell) q.pixels_per_cell = static_cast<int>(*pixels_per_cell);
            q.solve = solve && !pixels_per_cell;
            // The grid a solved pinhole lands on: fab_grid, or the export preset vendor's
            // (design/optics/design_run checks them).
            if (!fab_grid.is_none()) {
                q.fab_grid_m = length_value(fab_grid, "fab_grid", false);
                q.fab_grid_text = py::str(fab_grid).cast<std::string>();
            }
            if (vendor) {
                q.vendor = *vendor;
                if (const VendorPreset* p = find_vendor_preset(*vendor))
                    q.vendor_grid_m = p->grid_m;
            }
            // Where the camera came from, in this face's words (design --json's input_sources).
            for (const char* symbol : kCameraInputSymbols)
                q.input_sources.emplace_back(symbol,
                                             camera ? "camera argument" : "paper preset default");
            q.spell = [](const std::string& w) { return spell_fields(w, &optics_keyword); };
            const DesignReport r = run_design_request(q);
            if (!r.far_from_optimum.empty() &&
                PyErr_WarnEx(PyExc_UserWarning, ("pinmask: " + r.far_from_optimum).c_str(), 1) < 0)
                throw py::error_already_set();
            if (save_camera) io::write_camera_file(*save_camera, r.camera);
            return as_result(py::dict(json_value(io::design_json(r))));
        },
        py::arg("camera") = py::none(), py::arg("grid") = 16, py::arg("holes") = 20,
        py::arg("tiles") = 2, py::arg("kernel") = "auto", py::arg("lsi_tolerance_px") = 1.0,
        py::arg("pixels_per_cell") = py::none(), py::arg("solve") = py::none(),
        py::arg("fab_grid") = py::none(), py::arg("vendor") = py::none(), py::arg("spacing") = 2.0,
        py::arg("save_camera") = py::none(),
        R"(What `pinmask design --json` prints for the same settings, as a Result (io/design_json:
one rendering): lengths in metres with _m suffixes; infinite values are None with the reason
under notes (key -> text); keys without a suffix and "_at_u" keys are at the working distance u,
"_at_inf" keys are the distant-object design values; camera {object_distance_m, lens_focal_m,
sensor_distance_m, wavelength_m, bandwidth_m, pixel_pitch_m, pinhole_m, sensor_px [cols, rows]}
(as reported: a solved pinhole on the grid), geometry {n, holes, tiles [rows, cols]}, the
working distance (whole_pixels_per_cell_at_u, pinhole_for_pixels_per_cell_m, period_at_u_px,
lsi_mismatch_at_u_px, object_distance_range_m [near, far] (far None: shift invariant to
infinity), optimum_pinhole_lensless_m, optimum_pinhole_with_lens_m, spot_spread_cells,
spot_spreads_beyond_cell), image_distance_at_u_m (1/v = 1/f' - 1/u), diffraction_first_zero_px
(lambda f / (d w)), spectrum {bandwidth_m, wavelengths [[m, weight]]: the band as the kernels
sample it}, kernel {support_px, enclosed_energy, support_capped; or not_built}, kernel_warnings
(psf's warnings for the kernel it would build; a keyword optics() lacks is named with the
functions that take it), spacing_cells, max_holes_at_spacing (the proven packing bound: no valid
placement of more pinholes exists), max_holes_reason, input_sources (camera symbol -> 'camera
argument' or 'paper preset default'; a solved pinhole says so). grid n (cells per side), holes
K, tiles per side, spacing (cells, as --spacing), kernel (kernel_models()), lsi_tolerance_px in
pixels. Solving the pinhole as `design --solve pinhole` / `--pixels-per-cell N`: solve='pinhole'
(N = the nearest whole number at u) or pixels_per_cell=N gives d for N whole pixels per cell at
u, snapped to the fabrication grid fab_grid (a length, '1um'; default 1 nm) or the export preset
vendor's; the report is then for that d, with fab_grid_m, pinhole_solved_m, pinhole_on_grid_m,
grid_pitch_shift_px and grid_period_shift_px. save_camera (a path, as --save-camera): writes
the camera reported (a solved pinhole included) as a *.camera.json.)");

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
