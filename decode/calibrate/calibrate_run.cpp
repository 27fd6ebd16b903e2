#include "decode/calibrate/calibrate_run.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/version.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask {

CalibrateReport run_calibrate_request(CalibrateRequest q) {
    // A Bayer RAW read as 2 x 2 blocks: capture pixels are binning x binning sensor pixels.
    q.mask.camera.pixel_pitch_m *= q.options.pixel_binning;
    CalibrateReport r;
    calibrate::CalibrationSummary& s = r.summary;
    s = calibrate::calibrate_point_source(q.capture, q.dark, q.mask, q.options);
    if (q.spell) s.dark_source = q.spell(s.dark_source);
    // The calibrated mask: the measured kernel and the measured geometry in its provenance.
    Mask& cal = r.calibrated;
    cal = q.mask;
    cal.psf.kernel = {"measured", q.kernel_file, {}};
    cal.psf.pixels_per_cell =
        std::max(1, static_cast<int>(std::lround(0.5 * (s.pitch_x_px + s.pitch_y_px))));
    cal.provenance.generator = PINMASK_GENERATOR("calibrate");
    auto& sc = cal.provenance.scores;
    sc["calibrated_rotation_deg"] = s.rotation_deg;
    sc["calibrated_pitch_x_px"] = s.pitch_x_px;
    sc["calibrated_pitch_y_px"] = s.pitch_y_px;
    sc["calibrated_position_x_px"] = s.position_x_px;
    sc["calibrated_position_y_px"] = s.position_y_px;
    sc["calibrated_missing_pinholes"] = static_cast<double>(s.missing.size());
    sc["calibrated_background"] = s.background;
    sc["calibrated_pinhole_side_m"] = s.fit.side_m;
    if (std::isfinite(s.optical_density)) sc["calibrated_optical_density"] = s.optical_density;
    r.kernel = measured_kernel(
        s.kernel.values, cal.psf.pixels_per_cell,
        "calibrate: fitted " + kernel_model_name(s.fit.family) + " kernel of " + q.capture_name);
    r.corrected = q.dark ? Plane(q.capture - *q.dark) : std::move(q.capture);
    return r;
}

}  // namespace pinmask
