// The capture pipeline around decode_plane(): validation of the inputs, dark-frame subtraction,
// the crop of one period (docs/design.md section 2: "any one full period decodes the scene") and
// the per-channel decode, run on one std::thread per channel.
//
// Notation: the capture is R x C pixels with one or three channels; the period is the PSF's size
// Pr x Pc (the mask's PSF is one period of the cyclic tiling). Rows are y (downwards), columns
// are x (rightwards); a crop corner is given as (row, col) of its top-left pixel.
#pragma once

#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "decode/capture/decoder.hpp"

namespace pinmask {

// Throws InvalidInput naming `what` when the image is empty or holds a NaN/Inf value (with the
// channel, row and column of the first one).
void check_image_finite(const Image& image, const std::string& what);

// Throws InvalidInput naming `what` when the PSF is empty or one pixel, not finite, or its sum is
// not > 0.
void check_psf(const Plane& psf, const std::string& what);

// capture - dark, channel by channel. `dark` must have the capture's rows and columns and either
// one channel (subtracted from every channel) or the capture's channel count; otherwise
// InvalidInput naming both sizes.
Image subtract_dark(const Image& capture, const Image& dark);

// Which window of the capture is decoded.
enum class CropMode {
    kCenter,  // the one period whose centre is the frame's centre (the paper's step 2)
    kNone,    // the whole frame; the PSF is zero-padded to it (psf2otf)
    kCorner,  // the period whose top-left pixel is (row, col)
};

struct CropSpec {
    CropMode mode = CropMode::kCenter;
    int row = 0;  // kCorner only: top-left row (y)
    int col = 0;  // kCorner only: top-left column (x)
};

// A window of the frame: top-left (row, col) and its size.
struct CropWindow {
    int row = 0, col = 0, rows = 0, cols = 0;
};

// The window a crop takes from a frame_rows x frame_cols capture for a period of
// period_rows x period_cols. kCenter: top-left ((R - Pr) / 2, (C - Pc) / 2), rounded down.
// kNone: the whole frame. Throws InvalidInput when the frame is smaller than one period
// (kCenter, kCorner), or a kCorner window leaves the frame (naming the corner and the sizes).
CropWindow crop_window(int frame_rows, int frame_cols, int period_rows, int period_cols,
                       const CropSpec& spec);

// The pixels of `window` (which must lie inside the image), every channel.
Image crop(const Image& image, const CropWindow& window);

// Decodes every channel of `capture` independently with decode_plane(). `psfs` holds one PSF
// shared by all channels or one per channel. Channels run in parallel, one std::thread each;
// a mono capture decodes its one channel on the calling thread. Results are in channel order;
// if channels fail, the error of the lowest-numbered failing channel is rethrown.
// `noise_sigmas`: empty, or one per channel, each channel's DecodeOptions::auto_noise_sigma.
std::vector<DecodeResult> decode_channels(const Image& capture, const std::vector<Plane>& psfs,
                                          const DecodeOptions& options,
                                          const std::vector<double>& noise_sigmas = {});

}  // namespace pinmask
