// Internals shared by the image file codecs (core/image/image_io.cpp, tiff_io.cpp, png_io.cpp,
// npy_io.cpp, jpeg_io.cpp). Not part of the public API; include only from those files and their
// tests.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "core/errors/error.hpp"
#include "core/image/image.hpp"
#include "core/image/image_io.hpp"
#include "core/limits/resource_limits.hpp"

namespace pinmask::detail {

// InvalidInput("image file '<path>': <problem>").
InvalidInput bad_image_file(const std::filesystem::path& path, const std::string& problem);

// Refuses, before allocating, an image of rows x cols x channels samples beyond kMaxImageSamples
// or whose doubles plus `extra_bytes` of decode buffers exceed the memory bound (check_memory,
// which counts what the process already holds). Returns the reservation of the decode buffers,
// to hold while decoding; the Image's sized constructor charges the doubles themselves.
MemoryReservation check_image_size(const std::filesystem::path& path, long long rows,
                                   long long cols, long long channels, double extra_bytes);

// Validates an image before writing: non-empty, 1 or 3 channels of equal size; for integer
// formats also every value finite (NaN cannot be quantised). Throws InvalidInput naming `path`.
void check_writable(const std::filesystem::path& path, const Image& image, SampleFormat format);

// Largest count of an integer format (255, 65535); 1.0 for float formats.
double full_scale_of(SampleFormat format);

// Bytes per sample: 1, 2, 4, 8.
int bytes_of(SampleFormat format);

// "uint8", "uint16", "float32", "float64".
const char* format_name(SampleFormat format);

// Integer count of a value in [0, 1]: clamp(v, 0, 1) * full_scale rounded to nearest (half away
// from zero). The value must be finite (check_writable ensured it).
std::uint32_t quantise(double v, double full_scale);

// Reads one sample stored in host byte order at p (libtiff delivers host order).
double load_host_sample(const unsigned char* p, SampleFormat format);

// Stores v as one sample in host byte order at p; integer formats take v in [0, 1] (quantised).
void store_host_sample(unsigned char* p, SampleFormat format, double v);

// The codecs behind read_image(); the caller has checked the magic bytes.
LoadedImage read_tiff(const std::filesystem::path& path);
LoadedImage read_png(const std::filesystem::path& path);
LoadedImage read_npy(const std::filesystem::path& path);
LoadedImage read_jpeg(const std::filesystem::path& path);

}  // namespace pinmask::detail
