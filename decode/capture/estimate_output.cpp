#include "decode/capture/estimate_output.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/name_table.hpp"
#include "core/image/image_io.hpp"

namespace pinmask {

void check_output_range(const Image& estimate, OutputKind kind) {
    if (kind == OutputKind::kPng) return;
    double peak = 0.0;
    for (const Plane& p : estimate.channels) peak = std::max(peak, p.abs().maxCoeff());
    if (peak > 3.4028234663852886e38) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3g", peak);
        throw invalid_field("-o", buf,
                            "the estimate exceeds the float32 range of .tif/.npy output "
                            "(|x| <= 3.4e38); scale the capture down or write a .png");
    }
}

OutputKind output_kind(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png") return OutputKind::kPng;
    if (ext == ".tif" || ext == ".tiff") return OutputKind::kTiff;
    if (ext == ".npy") return OutputKind::kNpy;
    throw invalid_field("-o", path.string(),
                        "the extension must be .png (scaled 8/16-bit), .tif/.tiff or .npy "
                        "(raw float32)");
}

const char* output_kind_name(OutputKind kind) {
    static constexpr NameTable<OutputKind, 3> kNames{{{OutputKind::kPng, "png"},
                                                      {OutputKind::kTiff, "tiff-float32"},
                                                      {OutputKind::kNpy, "npy-float32"}}};
    return name_or(kNames, kind, "?");
}

ScaledImage scale_for_png(const Image& estimate, std::optional<double> scale) {
    ScaledImage s;
    s.image = estimate;
    for (Plane& p : s.image.channels) {
        p = p.max(0.0);
        if (p.size() > 0) s.max_value = std::max(s.max_value, p.maxCoeff());
    }
    s.factor = scale ? *scale : (s.max_value > 0.0 ? 1.0 / s.max_value : 0.0);
    for (Plane& p : s.image.channels) p = (p * s.factor).min(1.0);
    return s;
}

void write_output_image(const std::filesystem::path& path, const Image& image, OutputKind kind,
                        int bits) {
    switch (kind) {
        case OutputKind::kPng:
            write_png(path, image, bits);
            return;
        case OutputKind::kTiff:
            write_tiff(path, image, SampleFormat::kFloat32);
            return;
        case OutputKind::kNpy:
            write_npy(path, image, SampleFormat::kFloat32);
            return;
    }
}

}  // namespace pinmask
