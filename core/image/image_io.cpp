// Format dispatch (magic bytes on read, extension on write) and the helpers the codecs share.
#include "core/image/image_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "core/errors/name_table.hpp"
#include "core/files/input_file.hpp"
#include "core/files/output_set.hpp"
#include "core/image/image_io_detail.hpp"
#include "core/image/raw_io.hpp"
#include "core/limits/resource_limits.hpp"

namespace pinmask {
namespace fs = std::filesystem;

namespace detail {

InvalidInput bad_image_file(const fs::path& path, const std::string& problem) {
    return InvalidInput("image file '" + path.string() + "': " + problem);
}

MemoryReservation check_image_size(const fs::path& path, long long rows, long long cols,
                                   long long channels, double extra_bytes) {
    if (rows <= 0 || cols <= 0) {
        throw bad_image_file(path, "declared size " + std::to_string(rows) + " x " +
                                       std::to_string(cols) + " is empty");
    }
    const double samples = double(rows) * double(cols) * double(channels);
    if (samples > double(kMaxImageSamples)) {
        throw bad_image_file(path, "declared size " + std::to_string(rows) + " x " +
                                       std::to_string(cols) + " x " + std::to_string(channels) +
                                       " exceeds the limit of " + std::to_string(kMaxImageSamples) +
                                       " samples (kMaxImageSamples)");
    }
    const std::string what = "reading image '" + path.string() + "'";
    check_memory(samples * sizeof(double) + extra_bytes, what);
    return MemoryReservation(extra_bytes >= kChargeThresholdBytes ? extra_bytes : 0.0, what);
}

void check_writable(const fs::path& path, const Image& image, SampleFormat format) {
    const auto fail = [&](const std::string& rule) {
        return InvalidInput("writing image '" + path.string() + "': " + rule);
    };
    if (image.empty()) throw fail("the image is empty");
    const int n = image.n_channels();
    if (n != 1 && n != 3) {
        throw fail("the image has " + std::to_string(n) + " channels: must be 1 (grey) or 3 (RGB)");
    }
    for (const Plane& p : image.channels) {
        if (p.rows() != image.rows() || p.cols() != image.cols()) {
            throw fail("channels differ in size");
        }
    }
    if (format == SampleFormat::kUint8 || format == SampleFormat::kUint16) {
        for (const Plane& p : image.channels) {
            if (!is_all_finite(p)) {
                throw fail(std::string("NaN or Inf values cannot be stored as ") +
                           format_name(format));
            }
        }
    }
}

double full_scale_of(SampleFormat format) {
    switch (format) {
        case SampleFormat::kUint8:
            return 255.0;
        case SampleFormat::kUint16:
            return 65535.0;
        default:
            return 1.0;
    }
}

int bytes_of(SampleFormat format) {
    switch (format) {
        case SampleFormat::kUint8:
            return 1;
        case SampleFormat::kUint16:
            return 2;
        case SampleFormat::kFloat32:
            return 4;
        default:
            return 8;
    }
}

const char* format_name(SampleFormat format) {
    static constexpr NameTable<SampleFormat, 4> kNames{{{SampleFormat::kUint8, "uint8"},
                                                        {SampleFormat::kUint16, "uint16"},
                                                        {SampleFormat::kFloat32, "float32"},
                                                        {SampleFormat::kFloat64, "float64"}}};
    return name_or(kNames, format, "float64");
}

std::uint32_t quantise(double v, double full_scale) {
    return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0, 1.0) * full_scale));
}

double load_host_sample(const unsigned char* p, SampleFormat format) {
    switch (format) {
        case SampleFormat::kUint8:
            return p[0];
        case SampleFormat::kUint16: {
            std::uint16_t v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }
        case SampleFormat::kFloat32: {
            float v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }
        default: {
            double v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }
    }
}

void store_host_sample(unsigned char* p, SampleFormat format, double v) {
    switch (format) {
        case SampleFormat::kUint8:
            p[0] = static_cast<unsigned char>(quantise(v, 255.0));
            break;
        case SampleFormat::kUint16: {
            const auto q = static_cast<std::uint16_t>(quantise(v, 65535.0));
            std::memcpy(p, &q, sizeof q);
            break;
        }
        case SampleFormat::kFloat32: {
            const auto f = static_cast<float>(v);
            std::memcpy(p, &f, sizeof f);
            break;
        }
        default:
            std::memcpy(p, &v, sizeof v);
    }
}

}  // namespace detail

namespace {

bool starts_with(const std::array<unsigned char, 8>& head, std::size_t n, const char* magic,
                 std::size_t len) {
    return n >= len && std::memcmp(head.data(), magic, len) == 0;
}

std::string hex_bytes(const std::array<unsigned char, 8>& head, std::size_t n) {
    std::string out;
    for (std::size_t i = 0; i < n; ++i) {
        char buf[4];
        std::snprintf(buf, sizeof buf, i ? " %02x" : "%02x", head[i]);
        out += buf;
    }
    return out;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace

LoadedImage read_image(const fs::path& path) {
    std::error_code ec;
    if (const auto problem = input_file_problem(path)) throw detail::bad_image_file(path, *problem);
    protect_input(path);  // no output of this run may replace it (core/files/output_set)
    std::ifstream in(path, std::ios::binary);
    if (!in) throw detail::bad_image_file(path, "cannot be opened for reading");
    std::array<unsigned char, 8> head{};
    in.read(reinterpret_cast<char*>(head.data()), head.size());
    const auto n = static_cast<std::size_t>(in.gcount());
    in.close();
    if (n == 0) throw detail::bad_image_file(path, "file is empty");
    // Camera RAW by extension (a DNG is a TIFF by its magic, but holds CFA data): LibRaw.
    if (is_raw_extension(path)) return read_raw(path);

    if (starts_with(head, n, "II*\0", 4) || starts_with(head, n, "MM\0*", 4) ||
        starts_with(head, n, "II+\0", 4) || starts_with(head, n, "MM\0+", 4)) {
        return detail::read_tiff(path);
    }
    if (starts_with(head, n, "\x89PNG\r\n\x1a\n", 8)) return detail::read_png(path);
    if (starts_with(head, n, "\x93NUMPY", 6)) return detail::read_npy(path);
    if (starts_with(head, n, "\xff\xd8\xff", 3)) return detail::read_jpeg(path);
    throw detail::bad_image_file(
        path, "unrecognised magic bytes [" + hex_bytes(head, n) + "] (" + std::to_string(n) +
                  " bytes read): expected a TIFF (II*/MM*), PNG (\\x89PNG), npy (\\x93NUMPY) "
                  "or JPEG (\\xff\\xd8\\xff) signature");
}

void write_image(const fs::path& path, const Image& image) {
    const std::string ext = lower(path.extension().string());
    if (ext == ".tif" || ext == ".tiff") {
        write_tiff(path, image, SampleFormat::kFloat32);
    } else if (ext == ".png") {
        write_png(path, image, 16);
    } else if (ext == ".npy") {
        write_npy(path, image, SampleFormat::kFloat32);
    } else {
        throw invalid_field("image file extension", "'" + path.extension().string() + "'",
                            "must be .tif, .tiff, .png or .npy (file '" + path.string() + "')");
    }
}

}  // namespace pinmask
