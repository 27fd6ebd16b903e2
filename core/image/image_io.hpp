// Image file I/O: TIFF (8/16-bit unsigned, 32-bit float; 1 or 3 channels), PNG (8/16-bit grey or
// RGB), .npy (float32/float64, little-endian, C order, shape (rows, cols) or (rows, cols, 3)),
// and JPEG (read only: lossy, so never written).
// Integer files are read as raw counts (a 16-bit pixel of 40000 reads as 40000.0); `full_scale`
// tells the caller the largest representable count (255, 65535; 1.0 for float files) so it can
// normalise. Writers take values in the target's own units for float formats and values in
// [0, 1] (clamped, rounded to nearest) for integer formats. Every write is atomic.
//
// What the readers accept beyond that (details at the top of tiff_io.cpp, png_io.cpp, npy_io.cpp,
// jpeg_io.cpp):
// - TIFF: the first page only; 64-bit float too; strips or tiles, contiguous or separate planes,
//   any compression the installed libtiff decodes; extra samples (alpha) are dropped.
// - PNG: palette images expand to 8-bit RGB, 1/2/4-bit grey to 8-bit grey (full scale 255);
//   alpha (grey+alpha, RGBA, palette transparency) is dropped; no gamma is applied.
// - npy: versions 1.0/2.0/3.0; also dtypes '|u1' and '<u2' (integer counts) and shape
//   (rows, cols, 1).
// - JPEG (libjpeg-turbo, 8-bit, full scale 255): baseline, progressive and arithmetic-coded;
//   greyscale -> 1 channel, YCbCr/RGB -> 3 channels RGB, decoded with the exact integer IDCT
//   (JDCT_ISLOW), so values equal other libjpeg readers'; no ICC or EXIF orientation applied.
//   Refused by name: CMYK/YCCK (Adobe), 12-bit and lossless JPEG, and any file libjpeg warns on
//   (a truncated or corrupt scan is refused, never padded with grey).
#pragma once

#include <filesystem>

#include "core/image/image.hpp"

namespace pinmask {

enum class SampleFormat { kUint8, kUint16, kFloat32, kFloat64 };

struct LoadedImage {
    Image image;
    SampleFormat format = SampleFormat::kFloat64;
    double full_scale = 1.0;
};

// Reads by content (magic bytes), not by extension. Throws InvalidInput naming the file and the
// problem for: missing/empty/truncated files, unsupported layouts (bit depths, channel counts,
// compression we cannot decode, big-endian npy, Fortran order), declared sizes beyond
// kMaxImageSamples or the memory bound (ResourceLimit, checked before allocating). NaN/Inf in
// float data is *not* an error here (callers decide).
LoadedImage read_image(const std::filesystem::path& path);

// Largest image (rows * cols * channels) the readers accept before allocating: 2^27 samples
// (1 GiB as double; 11585 px square grey, a 6000 x 4000 RGB camera frame fits). Decoding keeps
// about six double or complex planes of the capture's size, so a larger image would need more
// than 6 GiB in the decoder: a 249 KB all-zero 16000 x 16000 PNG is refused from its header.
inline constexpr long long kMaxImageSamples = 1LL << 27;

void write_tiff(const std::filesystem::path& path, const Image& image, SampleFormat format);
void write_png(const std::filesystem::path& path, const Image& image, int bits);  // 8 or 16
void write_npy(const std::filesystem::path& path, const Image& image, SampleFormat format);

// Writes by extension: .tif/.tiff -> float32 TIFF, .png -> 16-bit PNG, .npy -> float32 npy.
// Throws InvalidInput for an unknown extension.
void write_image(const std::filesystem::path& path, const Image& image);

}  // namespace pinmask
