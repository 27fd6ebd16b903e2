// calibrate() is `pinmask calibrate` on arrays: the command's transaction
// decode/calibrate/calibrate_run with its options and refusals (messages name the keywords through
// python/keyword_names), returning io/calibrate_json's rendering of `pinmask calibrate --json`
// with the PSFs and kernel as arrays in place of the written files' paths, and the residual map.
#include <cmath>
#include <limits>
#include <optional>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "decode/calibrate/calibrate_run.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/calibrate_json.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/keyword_names.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

void bind_calibrate(py::module_& m) {
    m.def(
        "calibrate",
        [](const py::handle& point, const py::handle& mask_obj, const py::handle& dark_obj,
           double max_rotation, double pitch_range, double threshold, const py::handle& saturation,
           int pixel_binning) {
            CalibrateRequest q;
            q.mask = mask_arg(mask_obj);
            PlaneArg cap = plane_arg(point, "point");
            if (!dark_obj.is_none()) q.dark = plane_arg(dark_obj, "dark").take();
            calibrate::CalibrationOptions& o = q.options;
            o.max_rotation_deg = max_rotation;
            o.pitch_range = pitch_range;
            o.threshold_sigmas = threshold;
            o.saturation_level = saturation.is_none() ? std::numeric_limits<double>::infinity()
                                                      : saturation.cast<double>();
            o.detect_saturation = saturation.is_none();  // as the command's --saturation auto
            o.pixel_binning = pixel_binning;
            q.capture = cap.take();
            q.capture_name = "point";
            q.spell = [](const std::string& w) { return py_names::spell_keywords(w); };
            CalibrateReport r;
            {
                py::gil_scoped_release release;
                r = run_calibrate_request(std::move(q));
            }
            // `calibrate --json`'s dict with arrays in place of its files (psf, psf_period,
            // kernel; no calibrated mask or report file), and the residual map.
            calibrate::CalibrationSummary& s = r.summary;
            // The command's "pinmask: warning:" lines, as Python warnings.
            for (const std::string& w : s.warnings) {
                const std::string text = "pinmask: " + py_names::spell_keywords(w);
                if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1) < 0)
                    throw py::error_already_set();
            }
            py::dict j = json_value(io::calibration_result_json(s, ""));
            j.attr("pop")("mask");
            j.attr("pop")("report");
            j["psf"] = to_array(std::move(s.psfs.full_frame));
            j["psf_period"] = s.psfs.period ? py::object(to_array(std::move(*s.psfs.period)))
                                            : py::object(py::none());
            j["kernel"] = to_array(std::move(s.kernel.values));
            j["residual_map"] = to_array(std::move(s.residual_map));
            return as_result(j);
        },
        py::arg("point"), py::arg("mask"), py::arg("dark") = py::none(),
        py::arg("max_rotation_deg") = CalibrateRequest{}.options.max_rotation_deg,
        py::arg("pitch_range") = CalibrateRequest{}.options.pitch_range,
        py::arg("threshold_sigmas") = CalibrateRequest{}.options.threshold_sigmas,
        py::arg("saturation_level") = py::none(),
        py::arg("pixel_binning") = CalibrateRequest{}.options.pixel_binning,
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
