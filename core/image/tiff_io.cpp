// TIFF codec over libtiff. Reads the first directory (page) of 8/16-bit unsigned or 32/64-bit
// float files, grey (MinIsBlack) or RGB, contiguous or separate planes, strips or tiles, any
// compression this libtiff decodes; extra samples (alpha) are dropped. Writes uncompressed,
// contiguous, little-endian-on-x86 (host order) files with a fixed tag set (no date, no software
// tag), so equal images give byte-identical files. libtiff's messages never reach stderr: errors
// are captured per thread and put into the exception, warnings are dropped.
#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/files/atomic_file.hpp"
#include "core/image/image_io.hpp"
#include "core/image/image_io_detail.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

// Largest single allocation libtiff may make for one file: a scanline or tile of the largest
// image we accept (kMaxImageSamples doubles).
constexpr tmsize_t kMaxTiffSingleAlloc = static_cast<tmsize_t>(kMaxImageSamples) * 8;
// Captured error text is capped so a corrupt file cannot grow it without bound.
constexpr std::size_t kMaxErrorText = 2000;

thread_local std::string t_tiff_error;

void append_error(const char* module, const char* fmt, va_list ap) {
    char buf[512];
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    try {
        if (t_tiff_error.size() > kMaxErrorText) return;
        if (!t_tiff_error.empty()) t_tiff_error += "; ";
        if (module && *module) {
            t_tiff_error += module;
            t_tiff_error += ": ";
        }
        t_tiff_error += buf;
    } catch (...) {  // out of memory while reporting: keep what we have
    }
}

void on_global_error(const char* module, const char* fmt, va_list ap) {
    append_error(module, fmt, ap);
}

int on_error(TIFF*, void*, const char* module, const char* fmt, va_list ap) {
    append_error(module, fmt, ap);
    return 1;  // handled: do not call the global handler too
}

int on_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

void install_global_handlers() {
    // Messages libtiff reports without a handle go through the process-wide handlers.
    static const bool installed = [] {
        TIFFSetErrorHandler(on_global_error);
        TIFFSetWarningHandler(nullptr);
        return true;
    }();
    (void)installed;
}

struct TiffCloser {
    void operator()(TIFF* t) const { TIFFClose(t); }
};
using TiffPtr = std::unique_ptr<TIFF, TiffCloser>;

TiffPtr open_tiff(const fs::path& path, const char* mode) {
    install_global_handlers();
    t_tiff_error.clear();
    TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
    if (!opts) throw RuntimeFailure("libtiff: out of memory");
    TIFFOpenOptionsSetErrorHandlerExtR(opts, on_error, nullptr);
    TIFFOpenOptionsSetWarningHandlerExtR(opts, on_warning, nullptr);
    TIFFOpenOptionsSetMaxSingleMemAlloc(opts, kMaxTiffSingleAlloc);
    TIFF* tif = TIFFOpenExt(path.c_str(), mode, opts);
    TIFFOpenOptionsFree(opts);
    return TiffPtr(tif);
}

std::string tiff_error(const char* fallback) {
    return t_tiff_error.empty() ? std::string(fallback) : t_tiff_error;
}

const char* photometric_name(uint16_t p) {
    switch (p) {
        case PHOTOMETRIC_MINISWHITE:
            return "MinIsWhite";
        case PHOTOMETRIC_PALETTE:
            return "Palette";
        case PHOTOMETRIC_MASK:
            return "TransparencyMask";
        case PHOTOMETRIC_SEPARATED:
            return "Separated (CMYK)";
        case PHOTOMETRIC_YCBCR:
            return "YCbCr";
        case PHOTOMETRIC_CIELAB:
            return "CIELab";
        default:
            return "unknown";
    }
}

SampleFormat sample_format(const fs::path& path, uint16_t bps, uint16_t sfmt) {
    if (sfmt == SAMPLEFORMAT_UINT && bps == 8) return SampleFormat::kUint8;
    if (sfmt == SAMPLEFORMAT_UINT && bps == 16) return SampleFormat::kUint16;
    if (sfmt == SAMPLEFORMAT_IEEEFP && bps == 32) return SampleFormat::kFloat32;
    if (sfmt == SAMPLEFORMAT_IEEEFP && bps == 64) return SampleFormat::kFloat64;
    const char* kind = sfmt == SAMPLEFORMAT_UINT     ? "unsigned integer"
                       : sfmt == SAMPLEFORMAT_INT    ? "signed integer"
                       : sfmt == SAMPLEFORMAT_IEEEFP ? "float"
                                                     : "complex or void";
    throw detail::bad_image_file(path, "TIFF samples are " + std::to_string(bps) + "-bit " + kind +
                                           ": supported are 8/16-bit unsigned and 32/64-bit float");
}

struct Layout {
    int rows = 0, cols = 0, channels = 0;
    int stride = 0;  // samples per pixel in one decoded buffer (spp if contiguous, else 1)
    int planes = 0;  // 1 if contiguous, else channels
    SampleFormat format = SampleFormat::kUint8;
};

// Copies `n` pixels of a decoded buffer into row r from column c0; plane selects the channel
// for separate planes.
void unpack(const unsigned char* src, const Layout& l, int plane, int r, int c0, int n,
            Image& image) {
    const int bytes = detail::bytes_of(l.format);
    const int n_ch = l.planes == 1 ? l.channels : 1;
    for (int k = 0; k < n_ch; ++k) {
        double* dst = image.channels[l.planes == 1 ? k : plane].row(r).data() + c0;
        for (int c = 0; c < n; ++c) {
            dst[c] =
                detail::load_host_sample(src + (std::size_t(c) * l.stride + k) * bytes, l.format);
        }
    }
}

void read_strips(TIFF* tif, const fs::path& path, const Layout& l, Image& image) {
    const tmsize_t line = TIFFScanlineSize(tif);
    const double need = double(l.cols) * l.stride * detail::bytes_of(l.format);
    if (line <= 0 || double(line) < need) {
        throw detail::bad_image_file(
            path, "TIFF scanline size is inconsistent: " + tiff_error("bad layout"));
    }
    std::vector<unsigned char> buf(static_cast<std::size_t>(line));
    for (int plane = 0; plane < l.planes; ++plane) {
        for (int r = 0; r < l.rows; ++r) {
            if (TIFFReadScanline(tif, buf.data(), static_cast<uint32_t>(r),
                                 static_cast<uint16_t>(plane)) < 0) {
                throw detail::bad_image_file(path, "TIFF data unreadable at row " +
                                                       std::to_string(r) +
                                                       " (truncated or "
                                                       "corrupt): " +
                                                       tiff_error("read error"));
            }
            unpack(buf.data(), l, plane, r, 0, l.cols, image);
        }
    }
}

void read_tiles(TIFF* tif, const fs::path& path, const Layout& l, Image& image) {
    uint32_t tw = 0, tl = 0;
    TIFFGetField(tif, TIFFTAG_TILEWIDTH, &tw);
    TIFFGetField(tif, TIFFTAG_TILELENGTH, &tl);
    const tmsize_t size = TIFFTileSize(tif);
    const double need = double(tw) * tl * l.stride * detail::bytes_of(l.format);
    if (tw == 0 || tl == 0 || size <= 0 || double(size) < need) {
        throw detail::bad_image_file(
            path, "TIFF tile size is inconsistent: " + tiff_error("bad tile layout"));
    }
    std::vector<unsigned char> buf(static_cast<std::size_t>(size));
    const std::size_t row_bytes = std::size_t(tw) * l.stride * detail::bytes_of(l.format);
    for (int plane = 0; plane < l.planes; ++plane) {
        for (uint32_t y0 = 0; y0 < uint32_t(l.rows); y0 += tl) {
            for (uint32_t x0 = 0; x0 < uint32_t(l.cols); x0 += tw) {
                if (TIFFReadTile(tif, buf.data(), x0, y0, 0, static_cast<uint16_t>(plane)) < 0) {
                    throw detail::bad_image_file(
                        path,
                        "TIFF tile at (" + std::to_string(y0) + ", " + std::to_string(x0) +
                            ") unreadable (truncated or corrupt): " + tiff_error("read error"));
                }
                const int n = static_cast<int>(std::min<uint32_t>(tw, uint32_t(l.cols) - x0));
                const uint32_t y1 = std::min<uint32_t>(y0 + tl, uint32_t(l.rows));
                for (uint32_t r = y0; r < y1; ++r) {
                    unpack(buf.data() + (r - y0) * row_bytes, l, plane, int(r), int(x0), n, image);
                }
            }
        }
    }
}

}  // namespace

namespace detail {

LoadedImage read_tiff(const fs::path& path) {
    TiffPtr tif = open_tiff(path, "r");
    if (!tif) {
        throw bad_image_file(path, "not a readable TIFF (truncated or corrupt header): " +
                                       tiff_error("TIFFOpen failed"));
    }
    TIFF* t = tif.get();
    uint32_t width = 0, height = 0;
    uint16_t bps = 1, spp = 1, sfmt = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG;
    uint16_t photometric = 0, compression = COMPRESSION_NONE;
    TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &width);
    TIFFGetField(t, TIFFTAG_IMAGELENGTH, &height);
    TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bps);
    TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &spp);
    TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &sfmt);
    TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &planar);
    TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
    if (!TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photometric)) {
        throw bad_image_file(path, "TIFF has no PhotometricInterpretation tag");
    }

    Layout l;
    l.format = sample_format(path, bps, sfmt);
    if (photometric == PHOTOMETRIC_MINISBLACK) {
        l.channels = 1;
    } else if (photometric == PHOTOMETRIC_RGB) {
        l.channels = 3;
    } else {
        throw bad_image_file(path, std::string("TIFF photometric interpretation ") +
                                       photometric_name(photometric) + " (" +
                                       std::to_string(photometric) +
                                       ") is not supported: only MinIsBlack grey and RGB");
    }
    uint16_t n_extra = 0;
    uint16_t* extra_types = nullptr;
    TIFFGetFieldDefaulted(t, TIFFTAG_EXTRASAMPLES, &n_extra, &extra_types);
    if (spp != l.channels + n_extra) {
        throw bad_image_file(path, "TIFF has " + std::to_string(spp) + " samples per pixel with " +
                                       std::to_string(n_extra) + " extra samples: expected " +
                                       std::to_string(l.channels) + " colour samples");
    }
    if (!TIFFIsCODECConfigured(compression)) {
        throw bad_image_file(path, "TIFF compression scheme " + std::to_string(compression) +
                                       " is not supported by this libtiff build");
    }
    l.rows = static_cast<int>(std::min<uint32_t>(height, 1u << 30));
    l.cols = static_cast<int>(std::min<uint32_t>(width, 1u << 30));
    const bool contiguous = planar == PLANARCONFIG_CONTIG;
    l.stride = contiguous ? spp : 1;
    l.planes = contiguous ? 1 : l.channels;
    const bool tiled = TIFFIsTiled(t);
    const double buffer = tiled ? double(TIFFTileSize64(t)) : double(TIFFScanlineSize64(t));
    const MemoryReservation decode_buffers =
        check_image_size(path, height, width, l.channels, buffer);

    LoadedImage out;
    out.image = Image(l.rows, l.cols, l.channels);
    out.format = l.format;
    out.full_scale = full_scale_of(l.format);
    if (tiled) {
        read_tiles(t, path, l, out.image);
    } else {
        read_strips(t, path, l, out.image);
    }
    return out;
}

}  // namespace detail

void write_tiff(const fs::path& path, const Image& image, SampleFormat format) {
    detail::check_writable(path, image, format);
    const int rows = image.rows(), cols = image.cols(), n_ch = image.n_channels();
    const int bytes = detail::bytes_of(format);
    const bool is_float = format == SampleFormat::kFloat32 || format == SampleFormat::kFloat64;
    const std::size_t row_bytes = std::size_t(cols) * n_ch * bytes;
    // About 64 KiB per strip: a fixed function of the size, so files are reproducible.
    const auto rows_per_strip =
        static_cast<uint32_t>(std::max<std::size_t>(1, (std::size_t(1) << 16) / row_bytes));
    write_file_atomic(path, [&](const fs::path& tmp) {
        TiffPtr tif = open_tiff(tmp, "w");
        if (!tif)
            throw RuntimeFailure("cannot create TIFF '" + tmp.string() +
                                 "': " + tiff_error("TIFFOpen failed"));
        TIFF* t = tif.get();
        TIFFSetField(t, TIFFTAG_IMAGEWIDTH, static_cast<uint32_t>(cols));
        TIFFSetField(t, TIFFTAG_IMAGELENGTH, static_cast<uint32_t>(rows));
        TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, static_cast<uint16_t>(8 * bytes));
        TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, static_cast<uint16_t>(n_ch));
        TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, is_float ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT);
        TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
        TIFFSetField(t, TIFFTAG_PHOTOMETRIC, n_ch == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
        TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_NONE);
        TIFFSetField(t, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
        TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, rows_per_strip);
        std::vector<unsigned char> row(row_bytes);
        for (int r = 0; r < rows; ++r) {
            for (int c = 0; c < cols; ++c) {
                for (int k = 0; k < n_ch; ++k) {
                    detail::store_host_sample(row.data() + (std::size_t(c) * n_ch + k) * bytes,
                                              format, image.channels[k](r, c));
                }
            }
            if (TIFFWriteScanline(t, row.data(), static_cast<uint32_t>(r), 0) < 0) {
                throw RuntimeFailure("writing TIFF '" + path.string() +
                                     "' failed: " + tiff_error("write error"));
            }
        }
        if (!TIFFFlush(t) || !t_tiff_error.empty()) {
            throw RuntimeFailure("writing TIFF '" + path.string() +
                                 "' failed: " + tiff_error("flush error"));
        }
        tif.reset();
        if (!t_tiff_error.empty()) {
            throw RuntimeFailure("closing TIFF '" + path.string() + "' failed: " + t_tiff_error);
        }
    });
}

}  // namespace pinmask
