#include "decode/depthmap/depthmap_capture.hpp"

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/number_format.hpp"
#include "decode/capture/preprocess.hpp"

namespace pinmask {

PreparedDepthCapture prepare_depth_capture(const Image& im, const DepthmapCaptureOptions& o,
                                           Mask* mask, std::vector<PsfStackPlane>* stack) {
    if (o.downsample < 0 || o.downsample > 12) {
        throw invalid_field(field_ref("downsample"), std::to_string(o.downsample),
                            "must be between 0 and 12 rounds of 2x2 averaging");
    }
    PreparedDepthCapture out;
    out.capture = Plane::Zero(im.rows(), im.cols());
    for (const Plane& ch : im.channels) out.capture += ch;
    out.capture /= static_cast<double>(im.n_channels());
    switch (o.background.mode) {
        case BackgroundMode::kNone:
            break;
        case BackgroundMode::kAuto:
            throw invalid_field(field_ref("background"), "auto",
                                "not for a depth sweep: give corner (each image's corner patch), "
                                "a number of counts or none");
        case BackgroundMode::kValue: {
            const double b = o.background.value, peak = out.capture.abs().maxCoeff();
            if (!std::isfinite(b) || std::abs(b) > peak) {
                throw invalid_field(field_ref("background"), format_number(b),
                                    "must be finite and not exceed the capture's largest "
                                    "magnitude " +
                                        format_number(peak) + " counts (it would leave no scene)");
            }
            out.background = b;
            break;
        }
        case BackgroundMode::kCorner:
            out.background = corner_background(out.capture);
            if (stack) {
                for (PsfStackPlane& p : *stack) p.psf = (p.psf - corner_background(p.psf)).max(0.0);
            }
            break;
    }
    out.capture -= out.background;
    if (o.downsample > 0) {
        out.capture = box_downsample(out.capture, o.downsample);
        if (stack) {
            for (PsfStackPlane& p : *stack) p.psf = box_downsample(p.psf, o.downsample);
        }
        if (mask) {
            const int f = 1 << o.downsample;
            mask->camera.pixel_pitch_m *= f;
            mask->camera.sensor_rows = std::max(1, mask->camera.sensor_rows / f);
            mask->camera.sensor_cols = std::max(1, mask->camera.sensor_cols / f);
        }
    }
    return out;
}

}  // namespace pinmask
