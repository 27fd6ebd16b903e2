#include "decode/calibrate/saturation.hpp"

#include "core/errors/error.hpp"
#include "core/units/number_format.hpp"

namespace pinmask::calibrate {

SaturatedPlateau find_saturated_plateau(const Plane& capture) {
    SaturatedPlateau p;
    if (capture.size() == 0) return p;
    p.level = capture.maxCoeff();
    const Eigen::Index rows = capture.rows(), cols = capture.cols();
    bool flat_top = false;
    for (Eigen::Index c = 0; c < cols; ++c)
        for (Eigen::Index r = 0; r < rows; ++r) {
            if (capture(r, c) != p.level) continue;
            ++p.pixels;
            if (flat_top) continue;
            int same = 0;
            if (r > 0 && capture(r - 1, c) == p.level) ++same;
            if (r + 1 < rows && capture(r + 1, c) == p.level) ++same;
            if (c > 0 && capture(r, c - 1) == p.level) ++same;
            if (c + 1 < cols && capture(r, c + 1) == p.level) ++same;
            flat_top = same >= 3;
        }
    p.found = flat_top && p.pixels >= kMinPlateauPixels;
    return p;
}

void check_capture_scale(const Plane& capture) {
    if (capture.size() == 0) return;
    const double peak = capture.abs().maxCoeff();
    if (peak == 0.0 || (peak >= kMinCapturePeak && peak <= kMaxCapturePeak)) return;
    throw InvalidInput("calibrate: the capture's scale is out of range: its largest value is " +
                       format_number(peak) + "; calibrate fits captures whose largest value lies " +
                       "between " + format_number(kMinCapturePeak) + " and " +
                       format_number(kMaxCapturePeak) +
                       " (counts, electrons or normalised units): multiply it by a constant "
                       "first");
}

}  // namespace pinmask::calibrate
