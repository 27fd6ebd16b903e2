// A Bayer mosaic saved in an ordinary image file (a Pi camera's raw dump as TIFF, a mosaic in
// .npy or PNG) and the sampling of a PSF against a capture read at half resolution.
//
// An image file holds no colour-filter pattern, so of the RAW reader's reductions
// (core/image/raw_io.hpp) only sum2x2 applies to it: the sum of each 2 x 2 block whose top-left
// is an even row and column (an odd last row or column is dropped), the pixel pitch doubled.
// green, r and b need the pattern and are refused for it, as is any reduction of an image with
// more than one channel (not a mosaic).
#pragma once

#include <filesystem>
#include <string>

#include "core/image/image_io.hpp"
#include "core/image/raw_io.hpp"

namespace pinmask {

// The 2 x 2 block sums of one plane (floor(rows / 2) x floor(cols / 2)). InvalidInput naming
// `what` when the plane is smaller than 2 x 2.
Plane sum_2x2_blocks(const Plane& p, const std::string& what);

// read_capture with the reduction the user asked for (`bayer` given): a camera RAW file as
// read_raw reads it; any other image file as a mosaic: sum2x2 applied to a single-channel
// image (info->binning 2, info->note says so), InvalidInput naming field_ref("bayer") for green,
// r, b (no pattern in the file) and for an image of several channels.
LoadedImage read_capture_as_mosaic(const std::filesystem::path& path, BayerMode bayer,
                                   RawInfo* info = nullptr);

// A PSF read at the sensor's full resolution for a capture binned 2 x 2 (`binning` 2): when the
// PSF is exactly twice the capture's size (2R or 2R + 1 rows, 2C or 2C + 1 columns) and the
// capture is 2 x 2 sums, the PSF is summed the same way and `note` says so; a PSF larger than the
// capture along an axis otherwise (green, r, b: the PSF's colour sites are unknown; any other
// size: no known relation) is refused (InvalidInput naming field_ref("bayer"), both sizes).
// Anything else (no binning, a PSF no larger than the capture) is left alone. `psf` is replaced.
void match_psf_to_binned_capture(Plane& psf, int capture_rows, int capture_cols,
                                 const RawInfo& capture_info, std::string& note);

// The same check where one PSF serves many captures (decode --batch, decode_batch): the PSF is
// not binned per capture, so a PSF that match_psf_to_binned_capture would bin is refused too,
// saying so (InvalidInput naming field_ref("psf"), both sizes); the refusals above stand. Only
// the sizes are read: a batch checks each capture without copying its PSF.
void check_shared_psf_sampling(int psf_rows, int psf_cols, int capture_rows, int capture_cols,
                               const RawInfo& capture_info);

}  // namespace pinmask
