// Image outputs named by a flag: the extension check before any work, writing a staged temporary
// in the format of the final name's extension, and the PNG clipping warning.
#pragma once

#include <filesystem>
#include <string>

#include "core/image/image.hpp"

namespace pinmask::cli {

// InvalidInput naming `flag` unless `path` ends in .tif/.tiff/.png/.npy (any case) and its
// directory exists.
void check_image_extension(const std::string& path, const std::string& flag);

// Writes `image` to tmp in the format of final_path's extension (already checked): float32 TIFF,
// 16-bit PNG of [0, 1], float32 npy.
void write_image_as(const std::filesystem::path& tmp, const std::filesystem::path& final_path,
                    const Image& image);

// A PNG holds [0, 1]: warns on stderr ("<who>: warning: ...") when `path` is a PNG and `image`
// has values outside, rather than hide the clipping.
void warn_png_clipping(const std::string& who, const std::string& path, const Image& image);

// A warning when every value of `image` is 0 (below 1e-30) or all are equal: a result that is all
// zero or flat (a photon level or full
// well so small that nothing is counted, an NSR so large the filter passes nothing) is said, never
// a silent success. `what` names it ("the capture", "the estimate") and `hint` the likely cause.
void warn_all_zero(const std::string& who, const std::string& what, const Image& image,
                   const std::string& hint);

}  // namespace pinmask::cli
