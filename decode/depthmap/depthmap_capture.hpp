// The capture preparation of a depth sweep, with decode's steps (decode/capture/preprocess):
// the capture as grey (channels averaged), a background off it, k rounds of 2 x 2 box averaging.
//   background none:   nothing subtracted;
//   background value:  that many counts off the capture (at most its largest magnitude, as
//                      decode refuses);
//   background corner: the tutorial's corner patch (rows and columns 5 .. 14) of each image off
//                      that image: the capture's off the capture, each stack PSF's off that PSF,
//                      clipped at 0 (a stack need not share the capture's counts, so each image
//                      has its own floor);
//   background auto:   refused (decode's auto reads a single PSF's floor; say corner or a value).
//   downsample k:      the capture and every stack PSF binned by 2^k per side
//                      (box_downsample); a mask's PSFs are drawn at the binned pixel pitch
//                      (pixel pitch x 2^k, sensor / 2^k), which is the binned exact PSF for
//                      spots integrated over pixels.
#pragma once

#include <vector>

#include "core/image/image.hpp"
#include "decode/capture/decode_request.hpp"
#include "decode/depthmap/depthmap.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask {

struct DepthmapCaptureOptions {
    DecodeBackground background{BackgroundMode::kNone, 0.0};
    int downsample = 0;  // rounds of 2 x 2 averaging, 0..12
};

struct PreparedDepthCapture {
    Plane capture;
    double background = 0;  // subtracted from the capture
};

// InvalidInput naming `background` or `downsample`. The mask (when given) is rescaled for the
// binning and each stack PSF is prepared in place.
PreparedDepthCapture prepare_depth_capture(const Image& capture,
                                           const DepthmapCaptureOptions& options, Mask* mask,
                                           std::vector<PsfStackPlane>* stack);

}  // namespace pinmask
