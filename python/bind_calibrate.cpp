// calibrate() is `pinmask calibrate` on arrays: calibrate_point_source (decode/calibrate/calibrate)
// with the CLI's options and refusals (messages name the keywords through python/keyword_names),
// returning a dict with the keys and values of `pinmask calibrate --json`
// (cli/outputs/calibrate_json) except the written files' paths, and the PSFs, kernel and residual
// map as arrays instead.
#include <cmath>
#include <limits>
#include <optional>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "decode/calibrate/calibrate.hpp"
#include "design/psf/kernel_model.hpp"
#include "python/common.hpp"
#include "python/keyword_names.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

py::list cells_list(const std::vector<Cell>& cells) {
    py::list l;
    for (const Cell& c : cells) l.append(py::make_tuple(c.row, c.col));
    return l;
}

py::object finite_or_none(double v) {
    return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
}

py::dict result_dict(calibrate::CalibrationSummary&& s) {
    const calibrate::ForwardFit& f = s.fit;
    py::dict j;
    j["rotation_convention"] =
        "counter-clockwise on screen with rows running down (scipy.ndimage.rotate's sense)";
    j["rotation_deg"] = s.rotation_deg;
    j["rotation_sigma_deg"] = s.rotation_sigma_deg;
    j["pitch_px"] = py::make_tuple(s.pitch_x_px, s.pitch_y_px);
    j["pitch_sigma_px"] = py::make_tuple(s.pitch_x_sigma_px, s.pitch_y_sigma_px);
    j["design_pitch_px"] = s.design_pitch_px;
    j["position_px"] = py::make_tuple(s.position_x_px, s.position_y_px);
    j["position_sigma_px"] = s.position_sigma_px;
    j["first_full_tile"] = py::make_tuple(s.first_tile.row, s.first_tile.col);
    j["kernel_family"] = kernel_model_name(f.family);
    j["pinhole_side_m"] = f.side_m;
    j["pinhole_side_scale"] = f.side_scale;
    j["pinhole_side_scale_sigma"] = f.side_scale_sigma;
    int in_frame = 0;
    py::list pinholes;
    for (const auto& p : f.pinholes) {
        in_frame += p.in_frame ? 1 : 0;
        py::dict d;
        d["cell"] = py::make_tuple(p.mask_cell.row, p.mask_cell.col);
        d["position_px"] = py::make_tuple(p.x, p.y);
        d["gain"] = p.gain;
        d["gain_sigma"] = p.gain_sigma;
        d["in_frame"] = p.in_frame;
        d["missing"] = p.missing;
        pinholes.append(d);
    }
    j["pinholes"] = pinholes;
    j["pinholes_in_frame"] = in_frame;
    j["missing_pinholes"] = cells_list(s.missing);
    py::dict rule;
    rule["false_alarm"] = 0.5 * std::erfc(f.missing_z / std::sqrt(2.0));
    rule["z"] = f.missing_z;
    rule["rule"] = "gain + z sigma < median gain / 2";
    j["missing_rule"] = rule;
    j["median_gain"] = f.median_gain;
    py::list extra;
    for (const auto& e : s.extra_spots) extra.append(py::make_tuple(e[0], e[1]));
    j["extra_spots"] = extra;
    j["saturated_spots"] = s.saturated_spots.size();
    if (s.plateau.found) {
        py::dict plateau;
        plateau["pixels"] = s.plateau.pixels;
        plateau["level"] = s.plateau.level;
        j["saturated_plateau"] = plateau;
    } else {
        j["saturated_plateau"] = py::none();
    }
    j["background"] = s.background;
    j["background_sigma"] = finite_or_none(s.background_sigma);
    j["optical_density"] = finite_or_none(s.optical_density);
    j["optical_density_sigma"] = s.optical_density_sigma;
    j["optical_density_is_lower_bound"] = s.optical_density_is_bound;
    j["dark_level"] = finite_or_none(s.dark_level);
    j["dark_source"] = py_names::spell_keywords(s.dark_source);
    j["band"] = s.band;
    j["noise_sigma"] = s.noise_sigma;
    py::dict noise;
    noise["alpha"] = f.noise_alpha;
    noise["beta"] = f.noise_beta;
    j["noise_model"] = noise;
    j["chi2_reduced"] = f.chi2_reduced;
    j["unexplained_fraction"] = f.unexplained;
    j["fit_iterations"] = f.iterations;
    j["fit_converged"] = f.converged;
    py::dict fit, unavailable;
    for (const auto& m : s.kernel_fit) {
        if (m.available)
            fit[py::str(m.model)] = m.residual;
        else
            unavailable[py::str(m.model)] = m.reason;
    }
    j["kernel_fit"] = fit;
    j["kernel_models_unavailable"] = unavailable;
    j["kernel_best_model"] = s.best_model;
    j["psf_period_note"] = s.psfs.period_reason;
    // Arrays in place of the CLI's files.
    j["psf"] = to_array(std::move(s.psfs.full_frame));
    j["psf_period"] =
        s.psfs.period ? py::object(to_array(std::move(*s.psfs.period))) : py::object(py::none());
    j["kernel"] = to_array(std::move(s.kernel.values));
    j["residual_map"] = to_array(std::move(s.residual_map));
    return j;
}

}  // namespace

void bind_calibrate(py::module_& m) {
    m.def(
        "calibrate",
        [](const py::handle& point, const py::handle& mask_obj, const py::handle& dark_obj,
           double max_rotation, double pitch_range, double threshold, const py::handle& saturation,
           int pixel_binning) {
            const Mask mask = mask_arg(mask_obj);
            PlaneArg cap = plane_arg(point, "point");
            std::optional<Plane> dark;
            if (!dark_obj.is_none()) dark = plane_arg(dark_obj, "dark").take();
            calibrate::CalibrationOptions o;
            o.max_rotation_deg = max_rotation;
            o.pitch_range = pitch_range;
            o.threshold_sigmas = threshold;
            o.saturation_level = saturation.is_none() ? std::numeric_limits<double>::infinity()
                                                      : saturation.cast<double>();
            o.detect_saturation = saturation.is_none();  // as the command's --saturation auto
            o.pixel_binning = pixel_binning;
            Mask binned = mask;
            binned.camera.pixel_pitch_m *= pixel_binning;
            calibrate::CalibrationSummary s;
            {
                py::gil_scoped_release release;
                s = calibrate::calibrate_point_source(cap.get(), dark, binned, o);
            }
            // The command's "pinmask: warning:" lines, as Python warnings.
            for (const std::string& w : s.warnings) {
                const std::string text = "pinmask: " + py_names::spell_keywords(w);
                if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1) < 0)
                    throw py::error_already_set();
            }
            return as_result(result_dict(std::move(s)));
        },
        py::arg("point"), py::arg("mask"), py::arg("dark") = py::none(),
        py::arg("max_rotation_deg") = 5.0, py::arg("pitch_range") = 0.05,
        py::arg("threshold_sigmas") = 6.0, py::arg("saturation_level") = py::none(),
        py::arg("pixel_binning") = 1,
        R"(Fits the mask's forward model to a point-source capture, as `pinmask calibrate`:
rotation (degrees, counter-clockwise on screen with rows running down: scipy.ndimage.rotate's
sense), pitches, position, pinhole side, per-pinhole gains and missing pinholes, leak (optical
density), background, with standard errors from the Fisher information.

point: (rows, cols) capture; mask: a Mask or *.mask.json path (its camera must carry the sensor's
pixel pitch); dark: optional dark frame of the same size; saturation_level: counts (None, the
default, as --saturation auto: a flat top of at least 16 pixels at exactly the capture's largest
value is its ceiling, with a UserWarning, or a ValueError when most spots reach it; inf: no
ceiling, as --saturation none); pixel_binning: sensor pixels per capture pixel along each axis.
Returns the keys of `pinmask calibrate --json` (files replaced by the arrays psf, psf_period,
kernel, residual_map). ValueError (naming the keyword) when the fit cannot be trusted: too few
photons, a capture the model does not explain, a rotation beyond max_rotation_deg.

Example: r = pinmask.calibrate(point, "m.mask.json"); r["rotation_deg"], r["missing_pinholes"])");
}

}  // namespace pinmask::python
