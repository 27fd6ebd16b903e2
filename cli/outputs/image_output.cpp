#include "cli/outputs/image_output.hpp"

#include <algorithm>
#include <cctype>
#include <iostream>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"

namespace pinmask::cli {

namespace fs = std::filesystem;

namespace {

std::string lower_ext(const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext;
}

}  // namespace

void check_image_extension(const std::string& path, const std::string& flag) {
    const std::string ext = lower_ext(path);
    if (ext != ".tif" && ext != ".tiff" && ext != ".png" && ext != ".npy") {
        throw invalid_field(flag, path, "must end in .tif, .tiff (float32), .png (16-bit) or .npy");
    }
    const fs::path dir = fs::path(path).parent_path();
    if (!dir.empty() && !fs::is_directory(dir)) {
        throw invalid_field(flag, path, "the output directory does not exist");
    }
}

void write_image_as(const fs::path& tmp, const fs::path& final_path, const Image& image) {
    const std::string ext = lower_ext(final_path);
    if (ext == ".png") {
        write_png(tmp, image, 16);
    } else if (ext == ".npy") {
        write_npy(tmp, image, SampleFormat::kFloat32);
    } else {
        write_tiff(tmp, image, SampleFormat::kFloat32);
    }
}

void warn_png_clipping(const std::string& who, const std::string& path, const Image& image) {
    if (path.empty() || lower_ext(path) != ".png") return;
    double lo = 0.0, hi = 0.0;
    for (const Plane& ch : image.channels) {
        lo = std::min(lo, ch.minCoeff());
        hi = std::max(hi, ch.maxCoeff());
    }
    if (lo < 0.0 || hi > 1.0) {
        std::cerr << who << ": warning: " << path << ": values in [" << lo << ", " << hi
                  << "] are clipped to [0, 1] in a PNG; use .tiff or .npy for raw float values\n";
    }
}

void warn_all_zero(const std::string& who, const std::string& what, const Image& image,
                   const std::string& hint) {
    // Below 1e-30 in every sample counts as zero: no capture or estimate in electrons, counts or
    // normalised units is that small, and subnormal inputs (--photons 1e-320) produce such values.
    constexpr double kNegligible = 1e-30;
    double lo = 0.0, hi = 0.0;
    bool first = true;
    for (const Plane& ch : image.channels) {
        if (ch.size() == 0) continue;
        if ((ch.abs() >= kNegligible).any() == false) continue;
        const double a = ch.minCoeff(), b = ch.maxCoeff();
        lo = first ? a : std::min(lo, a);
        hi = first ? b : std::max(hi, b);
        first = false;
    }
    if (first) {
        std::cerr << who << ": warning: " << what
                  << " is all zero (every value below 1e-30: " << hint << ")\n";
    } else if (lo == hi) {
        std::cerr << who << ": warning: " << what << " is constant (every value " << lo << ": "
                  << hint << ")\n";
    }
}

}  // namespace pinmask::cli
