// `pinmask calibrate`'s inputs: the --saturation setting, and the point-source capture and dark
// frame read from files as one grey plane each.
#pragma once

#include <string>

#include "core/image/image.hpp"
#include "core/image/raw_io.hpp"
#include "decode/calibrate/calibrate.hpp"

namespace pinmask::cli {

// --saturation: auto (options.detect_saturation: a flat top found in a float capture; an integer
// file's largest count is the caller's to set once the capture is read), none, or a count;
// InvalidInput naming --saturation otherwise.
void apply_saturation_flag(const std::string& text, calibrate::CalibrationOptions& options);

// The image at `path` (camera RAW through `bayer`) as one plane, its channels summed; a note on
// how a RAW file was read goes to stderr. InvalidInput naming `what` and the file when it holds
// NaN or Inf. `full_scale` (optional) receives the file's largest count (1 for float files),
// `raw` how it was read (its binning).
Plane read_grey(const std::string& path, const std::string& what, BayerMode bayer,
                double* full_scale, RawInfo& raw);

}  // namespace pinmask::cli
