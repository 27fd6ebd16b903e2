// Camera and optics numbers (design/optics/camera.hpp, design/optics/optics.hpp,
// design/psf/kernel_model.hpp).
#include <cmath>
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
#include "python/common.hpp"
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
    d["pixels_per_cell_at_inf"] = r.pixels_per_cell_at_inf;
    d["integer_pixels_per_cell"] = wd.pixels_per_cell;
    d["integer_pixels_per_cell_at_inf"] = r.integer_pixels_per_cell;
    d["pinhole_for_integer_pixels_m"] = wd.pinhole_for_pixels_per_cell_m;
    d["pinhole_for_integer_pixels_at_inf_m"] = r.pinhole_for_integer_pixels_m;
    d["image_distance_at_u_m"] = image_distance_at_u_m(r.camera);
    d["diffraction_first_zero_px"] = diffraction_first_zero_px(r.camera);
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
    // The working distance (design/optics/working_distance.hpp), under design --json's keys.
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
           const py::object& fab_grid, const std::optional<std::string>& vendor, double spacing) {
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
            // The fabrication grid a solved pinhole lands on: fab_grid, else the vendor
            // preset's, else 1 nm.
            std::int64_t grid_nm = kDefaultFabGridNm;
            if (!fab_grid.is_none() && vendor)
                throw invalid_field(
                    field_ref("fab_grid"), std::string(py::str(fab_grid)),
                    "and " + field_ref("vendor") + " both set the grid: give one of them");
            if (!fab_grid.is_none()) {
                grid_nm = fab_grid_nm(length_value(fab_grid, "fab_grid", false), "fab_grid");
            } else if (vendor) {
                const VendorPreset* preset = find_vendor_preset(*vendor);
                if (!preset)
                    throw invalid_field(field_ref("vendor"), *vendor,
                                        "is a rule preset without a grid; give an export preset "
                                        "(pinmask export --vendor list) or " +
                                            field_ref("fab_grid"));
                grid_nm = fab_grid_nm(preset->grid_m, "vendor");
            }
            const bool solving = pixels_per_cell || solve;
            if ((!fab_grid.is_none() || vendor) && !solving)
                throw invalid_field(field_ref(!fab_grid.is_none() ? "fab_grid" : "vendor"),
                                    !fab_grid.is_none() ? std::string(py::str(fab_grid)) : *vendor,
                                    "sets the grid a solved pinhole lands on: use it with " +
                                        field_ref("solve") + "='pinhole' or " +
                                        field_ref("pixels_per_cell"));
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
            q.solve = solving && !pixels_per_cell;
            q.grid.grid_nm = grid_nm;
            q.spell = [](const std::string& w) { return spell_fields(w, &optics_keyword); };
            const DesignReport r = run_design_request(q);
            if (!r.far_from_optimum.empty() &&
                PyErr_WarnEx(PyExc_UserWarning, ("pinmask: " + r.far_from_optimum).c_str(), 1) < 0)
                throw py::error_already_set();
            py::dict d = optics_dict(r.optics, r.working, r.kernel.validity.warnings);
            py::dict spectrum;
            spectrum["bandwidth_m"] = r.camera.bandwidth_m;
            spectrum["wavelengths"] = band_wavelengths(r.camera);
            d["spectrum"] = spectrum;
            py::dict k;
            if (r.kernel.kernel) {
                k["support_px"] =
                    py::make_tuple(r.kernel.kernel->values.rows(), r.kernel.kernel->values.cols());
                k["enclosed_energy"] = r.kernel.kernel->enclosed_energy;
                k["support_capped"] = r.kernel.kernel->support_capped;
            } else {
                k["not_built"] = r.kernel.not_built;
            }
            d["kernel"] = k;
            if (r.snap.solved) {  // the keys `design --json` adds for a solved pinhole
                d["fab_grid_m"] = double(r.snap.grid_nm) * 1e-9;
                d["pinhole_solved_m"] = r.snap.exact_m;
                d["pinhole_on_grid_m"] = r.snap.on_grid_m;
                d["grid_pitch_shift_px"] = r.snap.pitch_shift_px;
                d["grid_period_shift_px"] = r.snap.pitch_shift_px * g.n;
            }
            // As `design --json`: the spacing rule's packing bound on the pinhole count.
            d["spacing_cells"] = spacing;
            d["max_holes_at_spacing"] = r.packing.count;
            d["max_holes_reason"] = r.packing.reason;
            return as_result(d);
        },
        py::arg("camera") = py::none(), py::arg("grid") = 16, py::arg("holes") = 20,
        py::arg("tiles") = 2, py::arg("kernel") = "auto", py::arg("lsi_tolerance_px") = 1.0,
        py::arg("pixels_per_cell") = py::none(), py::arg("solve") = py::none(),
        py::arg("fab_grid") = py::none(), py::arg("vendor") = py::none(), py::arg("spacing") = 2.0,
        "The optics report of `pinmask design --json` as a dict (same keys and numbers; lengths "
        "in metres with _m suffixes, infinite values as float('inf') where the CLI writes null "
        "and a note; keys without a suffix and \"_at_u\" keys are at the working distance u, "
        "\"_at_inf\" keys are the distant-object design values), the working distance "
        "included: whole_pixels_per_cell_at_u, "
        "pinhole_for_pixels_per_cell_m, period_at_u_px, lsi_mismatch_at_u_px, "
        "object_distance_range_m (near, far; far inf when shift invariant to infinity), "
        "optimum_pinhole_lensless_m, optimum_pinhole_with_lens_m, spot_spread_cells (cells), "
        "spot_spreads_beyond_cell, image_distance_at_u_m (1/v = 1/f' - 1/u; inf without a lens), "
        "diffraction_first_zero_px (lambda f / (d w)), kernel_warnings (psf's warnings for the "
        "kernel it would build; a keyword optics() lacks is named with the functions that take "
        "it), "
        "spectrum (bandwidth_m, wavelengths [(m, weight)]: the camera's band as the kernels "
        "sample it), kernel (support_px, enclosed_energy, support_capped; or not_built). grid n "
        "(cells per side), holes K, tiles per "
        "side, kernel (kernel_models()), lsi_tolerance_px in pixels. Solving the pinhole as "
        "`design --solve pinhole` / `--pixels-per-cell N`: solve='pinhole' (N = the nearest "
        "whole number at u) or pixels_per_cell=N gives d for N whole pixels per cell at u, "
        "snapped to the fabrication grid fab_grid (a length, '1um'; default 1 nm) or the export "
        "preset vendor's; the report is then for that d (camera holds it: save_camera writes "
        "it, as --save-camera) with fab_grid_m, pinhole_solved_m, pinhole_on_grid_m, "
        "grid_pitch_shift_px and grid_period_shift_px. spacing (cells, as --spacing): "
        "spacing_cells, max_holes_at_spacing (the proven packing bound: no valid placement of more "
        "pinholes exists) and max_holes_reason.");

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
