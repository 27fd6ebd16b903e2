// The decoded estimate as an output file, its format chosen by the extension.
//
// PNG scaling (documented in `pinmask decode --help`): negative values are clipped to 0, then
// every channel is multiplied by one factor: 1 / (the maximum over all channels) by default,
// or the --scale value; results above 1 clip to full white. TIFF and .npy hold the raw float32
// estimate (capture units), unscaled.
#pragma once

#include <filesystem>
#include <optional>

#include "core/image/image.hpp"

namespace pinmask {

enum class OutputKind { kPng, kTiff, kNpy };

// .png -> kPng, .tif/.tiff -> kTiff, .npy -> kNpy (case-insensitive); anything else throws
// InvalidInput naming the path and the extensions accepted.
OutputKind output_kind(const std::filesystem::path& path);

const char* output_kind_name(OutputKind kind);

// .tif/.npy hold float32: an estimate beyond the float32 range (|x| > 3.4e38) would be written
// as Inf, so it is refused (InvalidInput naming the output) instead.
void check_output_range(const Image& estimate, OutputKind kind);

// The PNG values in [0, 1] (before write_png's clamp) and the factor used. `scale` empty means
// 1 / max; a non-positive maximum (an all-dark estimate) gives factor 0, all black.
struct ScaledImage {
    Image image;
    double factor = 0.0;
    double max_value = 0.0;  // max over channels after clipping negatives
};
ScaledImage scale_for_png(const Image& estimate, std::optional<double> scale);

// Writes `image` to `path` in the given kind (PNG with `bits` 8 or 16 from [0, 1] values;
// TIFF/npy float32 raw values). Not atomic by itself: callers stage it.
void write_output_image(const std::filesystem::path& path, const Image& image, OutputKind kind,
                        int bits);

}  // namespace pinmask
