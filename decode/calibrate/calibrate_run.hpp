// The calibrate transaction: a point-source capture through the whole mask to the fitted
// geometry (decode/calibrate/calibrate), the calibrated mask (the measured kernel, the measured
// geometry in its provenance) and the measured kernel. One call (run_calibrate_request) for both
// faces; io/calibrate_json renders the result and writes its files. The faces read the capture,
// the dark frame and the mask.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "core/image/image.hpp"
#include "decode/calibrate/calibrate.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel.hpp"

namespace pinmask {

struct CalibrateRequest {
    Mask mask;  // the design, its camera as the capture's sensor (pixels before binning)
    Plane capture;
    std::optional<Plane> dark;                // same size, subtracted first
    std::string capture_name;                 // named in the kernel's source
    calibrate::CalibrationOptions options;    // pixel_binning scales the camera's pixel pitch
    std::string kernel_file = "kernel.tiff";  // the calibrated mask's measured kernel file
    // The face's spelling of the library's field references in the summary's words (identity
    // when not given).
    std::function<std::string(const std::string&)> spell;
};

struct CalibrateReport {
    calibrate::CalibrationSummary summary;
    Mask calibrated;  // the measured kernel, the measured geometry in provenance.scores
    Kernel kernel;    // the measured kernel at the calibrated pixels per cell
    Plane corrected;  // the capture less the dark frame (the report's picture)
};

CalibrateReport run_calibrate_request(CalibrateRequest request);

}  // namespace pinmask
