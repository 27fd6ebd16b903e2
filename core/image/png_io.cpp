// PNG codec over libpng. Reads 8/16-bit grey and RGB; palette images are expanded to RGB and
// 1/2/4-bit grey to 8-bit (full scale 255); an alpha channel (grey+alpha, RGBA, or a palette's
// tRNS transparency) is dropped, keeping grey or RGB. No gamma or colour-space conversion is
// applied: values are the stored counts. 16-bit samples are big-endian in the file.
// Writes 8 or 16-bit grey or RGB, non-interlaced, without time or text chunks, so equal images
// give byte-identical files.
//
// Error handling: libpng reports errors by longjmp to the setjmp point. Every setjmp lives in a
// small function whose frame holds no C++ object with a destructor; state shared with the
// C++ caller sits in plain structs, and buffers are owned by the caller's frame, which a longjmp
// never skips.
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <string>
#include <vector>

#include "core/files/atomic_file.hpp"
#include "core/image/image_io.hpp"
#include "core/image/image_io_detail.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

// Plain state shared across setjmp/longjmp: trivially destructible by design.
struct PngState {
    png_structp png = nullptr;
    png_infop info = nullptr;
    std::FILE* fp = nullptr;
    char message[256] = {};
    png_uint_32 width = 0, height = 0;
    int bit_depth = 0, channels = 0;
    std::size_t rowbytes = 0;
    png_bytep* rows = nullptr;  // caller-owned row pointers (read and write)
    int color_type = 0;         // write only
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp msg) {
    auto* st = static_cast<PngState*>(png_get_error_ptr(png));
    std::snprintf(st->message, sizeof st->message, "%s", msg ? msg : "unknown libpng error");
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// Reads the header and sets up the transforms. Returns false with st->message on error.
[[gnu::noinline]] bool png_read_header_c(PngState* st) {
    if (setjmp(png_jmpbuf(st->png))) return false;
    png_init_io(st->png, st->fp);
    png_read_info(st->png, st->info);
    const int color_type = png_get_color_type(st->png, st->info);
    const int depth = png_get_bit_depth(st->png, st->info);
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(st->png);
    if (color_type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(st->png);
    png_set_strip_alpha(st->png);  // also removes the alpha a palette's tRNS expands to
    png_set_interlace_handling(st->png);
    png_read_update_info(st->png, st->info);
    st->width = png_get_image_width(st->png, st->info);
    st->height = png_get_image_height(st->png, st->info);
    st->bit_depth = png_get_bit_depth(st->png, st->info);
    st->channels = png_get_channels(st->png, st->info);
    st->rowbytes = png_get_rowbytes(st->png, st->info);
    return true;
}

// Decodes all rows into st->rows and reads the trailing chunks (a missing IEND is an error).
[[gnu::noinline]] bool png_read_rows_c(PngState* st) {
    if (setjmp(png_jmpbuf(st->png))) return false;
    png_read_image(st->png, st->rows);
    png_read_end(st->png, nullptr);
    return true;
}

[[gnu::noinline]] bool png_write_c(PngState* st) {
    if (setjmp(png_jmpbuf(st->png))) return false;
    png_init_io(st->png, st->fp);
    png_set_IHDR(st->png, st->info, st->width, st->height, st->bit_depth, st->color_type,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(st->png, st->info);
    png_write_image(st->png, st->rows);
    png_write_end(st->png, nullptr);
    return true;
}

// Releases libpng structures and the file when the C++ frame unwinds.
struct ReadGuard {
    PngState& st;
    ~ReadGuard() {
        if (st.png) png_destroy_read_struct(&st.png, st.info ? &st.info : nullptr, nullptr);
        if (st.fp) std::fclose(st.fp);
    }
};

struct WriteGuard {
    PngState& st;
    ~WriteGuard() {
        if (st.png) png_destroy_write_struct(&st.png, st.info ? &st.info : nullptr);
        if (st.fp) std::fclose(st.fp);
    }
};

}  // namespace

namespace detail {

LoadedImage read_png(const fs::path& path) {
    PngState st;
    ReadGuard guard{st};
    st.fp = std::fopen(path.c_str(), "rb");
    if (!st.fp) throw bad_image_file(path, "cannot be opened for reading");
    st.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &st, on_png_error, on_png_warning);
    if (st.png) st.info = png_create_info_struct(st.png);
    if (!st.png || !st.info) throw RuntimeFailure("libpng: out of memory");
    if (!png_read_header_c(&st)) {
        throw bad_image_file(
            path, std::string("PNG header unreadable (truncated or corrupt): ") + st.message);
    }
    if ((st.channels != 1 && st.channels != 3) || (st.bit_depth != 8 && st.bit_depth != 16)) {
        throw bad_image_file(path, "PNG decodes to " + std::to_string(st.channels) +
                                       " channels of " + std::to_string(st.bit_depth) +
                                       " bits: expected grey or RGB, 8 or 16 bits");
    }
    const MemoryReservation decode_buffers = check_image_size(
        path, st.height, st.width, st.channels,
        double(st.height) * double(st.rowbytes) + double(st.height) * sizeof(void*));
    std::vector<unsigned char> data(std::size_t(st.height) * st.rowbytes);
    std::vector<png_bytep> rows(st.height);
    for (png_uint_32 r = 0; r < st.height; ++r)
        rows[r] = data.data() + std::size_t(r) * st.rowbytes;
    st.rows = rows.data();
    if (!png_read_rows_c(&st)) {
        throw bad_image_file(
            path, std::string("PNG data unreadable (truncated or corrupt): ") + st.message);
    }

    const int n_ch = st.channels, rows_n = int(st.height), cols_n = int(st.width);
    const bool wide = st.bit_depth == 16;
    LoadedImage out;
    out.image = Image(rows_n, cols_n, n_ch);
    out.format = wide ? SampleFormat::kUint16 : SampleFormat::kUint8;
    out.full_scale = full_scale_of(out.format);
    for (int r = 0; r < rows_n; ++r) {
        const unsigned char* src = rows[r];
        for (int c = 0; c < cols_n; ++c) {
            for (int k = 0; k < n_ch; ++k) {
                const std::size_t i = std::size_t(c) * n_ch + k;
                out.image.channels[k](r, c) =
                    wide ? double((src[2 * i] << 8) | src[2 * i + 1]) : double(src[i]);
            }
        }
    }
    return out;
}

}  // namespace detail

void write_png(const fs::path& path, const Image& image, int bits) {
    if (bits != 8 && bits != 16) {
        throw invalid_field("PNG bit depth", std::to_string(bits), "must be 8 or 16");
    }
    const SampleFormat format = bits == 8 ? SampleFormat::kUint8 : SampleFormat::kUint16;
    detail::check_writable(path, image, format);
    const int rows_n = image.rows(), cols_n = image.cols(), n_ch = image.n_channels();
    const double fs_count = detail::full_scale_of(format);
    const std::size_t rowbytes = std::size_t(cols_n) * n_ch * (bits / 8);
    std::vector<unsigned char> data(rowbytes * rows_n);
    std::vector<png_bytep> rows(rows_n);
    for (int r = 0; r < rows_n; ++r) {
        unsigned char* dst = data.data() + std::size_t(r) * rowbytes;
        rows[r] = dst;
        for (int c = 0; c < cols_n; ++c) {
            for (int k = 0; k < n_ch; ++k) {
                const std::size_t i = std::size_t(c) * n_ch + k;
                const std::uint32_t q = detail::quantise(image.channels[k](r, c), fs_count);
                if (bits == 8) {
                    dst[i] = static_cast<unsigned char>(q);
                } else {
                    dst[2 * i] = static_cast<unsigned char>(q >> 8);  // big-endian
                    dst[2 * i + 1] = static_cast<unsigned char>(q & 0xff);
                }
            }
        }
    }
    write_file_atomic(path, [&](const fs::path& tmp) {
        PngState st;
        WriteGuard guard{st};
        st.fp = std::fopen(tmp.c_str(), "wb");
        if (!st.fp) throw RuntimeFailure("cannot open '" + tmp.string() + "' for writing");
        st.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &st, on_png_error, on_png_warning);
        if (st.png) st.info = png_create_info_struct(st.png);
        if (!st.png || !st.info) throw RuntimeFailure("libpng: out of memory");
        st.width = static_cast<png_uint_32>(cols_n);
        st.height = static_cast<png_uint_32>(rows_n);
        st.bit_depth = bits;
        st.color_type = n_ch == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY;
        st.rows = rows.data();
        if (!png_write_c(&st)) {
            throw RuntimeFailure("writing PNG '" + path.string() + "' failed: " + st.message);
        }
        std::FILE* fp = st.fp;
        st.fp = nullptr;
        if (std::fflush(fp) != 0 || std::ferror(fp) != 0) {
            std::fclose(fp);
            throw RuntimeFailure("writing PNG '" + path.string() + "' failed: I/O error");
        }
        if (std::fclose(fp) != 0) {
            throw RuntimeFailure("closing PNG '" + path.string() + "' failed: I/O error");
        }
    });
}

}  // namespace pinmask
