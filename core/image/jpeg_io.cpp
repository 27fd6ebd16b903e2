// JPEG reader over libjpeg-turbo (8-bit samples). Baseline, extended (8-bit), progressive and
// arithmetic-coded files decode; greyscale stays 1 channel, YCbCr and RGB files become 3 channels
// of RGB; full scale 255 (SampleFormat::kUint8). The inverse DCT is JDCT_ISLOW (libjpeg's exact
// integer default) with libjpeg's default (fancy) chroma upsampling, so values equal those of
// other libjpeg-based readers (PIL, skimage) bit for bit. No colour management (ICC profiles are
// ignored) and no EXIF orientation: values are the stored pixels in stored order.
// Refused by name: CMYK and YCCK (Adobe) files, other component counts, 12-bit and lossless
// JPEG (which this libjpeg build cannot decode), progressive files of more than kMaxJpegScans
// scans (a decoding-time bound), and any file on which libjpeg warns (truncated scan, corrupt
// entropy data, missing EOI): a warning means libjpeg filled the rest with grey, and a capture
// with invented pixels must not be decoded as if it were real.
// No writer: JPEG is lossy, and pinmask's outputs are measurements.
//
// Error handling: libjpeg reports errors (and here warnings) through the error manager; ours
// formats the message into plain state and longjmps back to the setjmp point, never printing or
// exiting. As in png_io.cpp, every setjmp lives in a small function whose frame holds no C++
// object with a destructor; buffers are owned by the caller's frame, which a longjmp never skips.
// clang-format off
#include <cstdio>  // before jpeglib.h, which uses FILE and size_t without including them
#include <jpeglib.h>
// clang-format on

#include <csetjmp>
#include <string>
#include <vector>

#include "core/image/image_io.hpp"
#include "core/image/image_io_detail.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

// Plain state shared across setjmp/longjmp: trivially destructible by design. `err` is first, so
// the error manager libjpeg hands back is the state itself.
struct JpegState {
    jpeg_error_mgr err;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX] = {};
    bool warning = false;  // the longjmp came from a warning (corrupt or truncated data)
    bool multiple_scans = false;
    jpeg_progress_mgr progress;
    jpeg_decompress_struct cinfo;
    bool created = false;
    std::FILE* fp = nullptr;
    JSAMPROW* rows = nullptr;  // caller-owned row pointers
};

[[noreturn]] void on_jpeg_error(j_common_ptr cinfo) {
    auto* st = reinterpret_cast<JpegState*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, st->message);
    std::longjmp(st->jump, 1);
}

// Level -1 is a warning (libjpeg's corrupt-data reports: it would go on with invented samples);
// higher levels are trace messages, which are dropped.
void on_jpeg_message(j_common_ptr cinfo, int level) {
    if (level >= 0) return;
    auto* st = reinterpret_cast<JpegState*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, st->message);
    st->warning = true;
    std::longjmp(st->jump, 1);
}

void on_jpeg_output(j_common_ptr) {}

// A progressive file of a few hundred bytes can declare a large frame and then hundreds of
// valid (tiny) scans, each a pass over the whole image: minutes of decoding from a small file
// (libjpeg-turbo's own advice is a scan limit). Real progressive files have about 10 scans
// (jpeg_simple_progression), optimised scan scripts a few dozen.
constexpr int kMaxJpegScans = 500;

void on_jpeg_progress(j_common_ptr cinfo) {
    const auto* d = reinterpret_cast<j_decompress_ptr>(cinfo);
    if (d->input_scan_number <= kMaxJpegScans) return;
    auto* st = reinterpret_cast<JpegState*>(cinfo->err);
    std::snprintf(st->message, sizeof st->message,
                  "more than %d scans (kMaxJpegScans; a progressive file has about ten)",
                  kMaxJpegScans);
    std::longjmp(st->jump, 1);
}

[[gnu::noinline]] bool jpeg_create_c(JpegState* st) {
    st->cinfo.err = jpeg_std_error(&st->err);
    st->err.error_exit = on_jpeg_error;
    st->err.emit_message = on_jpeg_message;
    st->err.output_message = on_jpeg_output;
    if (setjmp(st->jump)) return false;
    jpeg_create_decompress(&st->cinfo);
    st->created = true;
    st->progress.progress_monitor = on_jpeg_progress;
    st->cinfo.progress = &st->progress;
    return true;
}

// Reads the header and chooses the output colour space. Returns false with st->message on error.
[[gnu::noinline]] bool jpeg_read_header_c(JpegState* st) {
    if (setjmp(st->jump)) return false;
    jpeg_stdio_src(&st->cinfo, st->fp);
    jpeg_read_header(&st->cinfo, TRUE);  // TRUE: a tables-only stream is an error
    st->cinfo.dct_method = JDCT_ISLOW;
    const J_COLOR_SPACE in = st->cinfo.jpeg_color_space;
    if (in == JCS_GRAYSCALE) st->cinfo.out_color_space = JCS_GRAYSCALE;
    if (in == JCS_YCbCr || in == JCS_RGB) st->cinfo.out_color_space = JCS_RGB;
    st->multiple_scans = jpeg_has_multiple_scans(&st->cinfo);
    return true;
}

// Decodes every scanline into st->rows, then reads to the EOI marker (a missing one warns).
[[gnu::noinline]] bool jpeg_read_rows_c(JpegState* st) {
    if (setjmp(st->jump)) return false;
    jpeg_start_decompress(&st->cinfo);
    while (st->cinfo.output_scanline < st->cinfo.output_height) {
        jpeg_read_scanlines(&st->cinfo, st->rows + st->cinfo.output_scanline,
                            st->cinfo.output_height - st->cinfo.output_scanline);
    }
    jpeg_finish_decompress(&st->cinfo);
    return true;
}

// Releases libjpeg's structures and the file when the C++ frame unwinds.
struct ReadGuard {
    JpegState& st;
    ~ReadGuard() {
        if (st.created) jpeg_destroy_decompress(&st.cinfo);
        if (st.fp) std::fclose(st.fp);
    }
};

std::string failure(const JpegState& st, const std::string& stage) {
    if (st.warning) {
        // libjpeg would go on, filling what it could not decode with grey.
        return "JPEG " + stage + " truncated or corrupt (" + st.message +
               (stage == "data" ? "): refused rather than decoded with invented samples" : ")");
    }
    return "JPEG " + stage + " unreadable (truncated, corrupt or unsupported): " + st.message;
}

}  // namespace

namespace detail {

LoadedImage read_jpeg(const fs::path& path) {
    JpegState st;
    ReadGuard guard{st};
    st.fp = std::fopen(path.c_str(), "rb");
    if (!st.fp) throw bad_image_file(path, "cannot be opened for reading");
    if (!jpeg_create_c(&st)) throw RuntimeFailure(std::string("libjpeg: ") + st.message);
    if (!jpeg_read_header_c(&st)) throw bad_image_file(path, failure(st, "header"));

    const J_COLOR_SPACE in = st.cinfo.jpeg_color_space;
    if (in == JCS_CMYK || in == JCS_YCCK) {
        throw bad_image_file(path, std::string(in == JCS_CMYK ? "CMYK" : "YCCK") +
                                       " (Adobe) JPEG: not supported, expected greyscale, YCbCr "
                                       "or RGB (convert it to RGB first)");
    }
    if (in != JCS_GRAYSCALE && in != JCS_YCbCr && in != JCS_RGB) {
        throw bad_image_file(path, "JPEG with " + std::to_string(st.cinfo.num_components) +
                                       " components in an unknown colour space: expected "
                                       "greyscale, YCbCr or RGB");
    }
    const long long rows_n = st.cinfo.image_height, cols_n = st.cinfo.image_width;
    const int n_ch = in == JCS_GRAYSCALE ? 1 : 3;
    // Decode buffers: the 8-bit output, its row pointers and, for a multi-scan (progressive)
    // file, libjpeg's whole-image coefficient arrays (2-byte coefficients over every component,
    // padded to 8 x 8 blocks; subsampled chroma needs less, so this bounds it from above).
    const double padded = double((rows_n + 15) / 8 * 8) * double((cols_n + 15) / 8 * 8);
    const double coefficients =
        st.multiple_scans ? padded * st.cinfo.num_components * sizeof(JCOEF) : 0.0;
    const MemoryReservation decode_buffers = check_image_size(
        path, rows_n, cols_n, n_ch,
        double(rows_n) * double(cols_n) * n_ch + double(rows_n) * sizeof(void*) + coefficients);

    const std::size_t rowbytes = std::size_t(cols_n) * n_ch;
    std::vector<unsigned char> data(std::size_t(rows_n) * rowbytes);
    std::vector<JSAMPROW> rows(static_cast<std::size_t>(rows_n));
    for (long long r = 0; r < rows_n; ++r) rows[r] = data.data() + std::size_t(r) * rowbytes;
    st.rows = rows.data();
    if (!jpeg_read_rows_c(&st)) throw bad_image_file(path, failure(st, "data"));
    if (int(st.cinfo.output_components) != n_ch || (long long)st.cinfo.output_height != rows_n ||
        (long long)st.cinfo.output_width != cols_n) {
        throw RuntimeFailure("libjpeg decoded '" + path.string() + "' to an unexpected layout");
    }

    LoadedImage out;
    out.image = Image(int(rows_n), int(cols_n), n_ch);
    out.format = SampleFormat::kUint8;
    out.full_scale = full_scale_of(out.format);
    for (long long r = 0; r < rows_n; ++r) {
        const unsigned char* src = rows[r];
        for (long long c = 0; c < cols_n; ++c) {
            for (int k = 0; k < n_ch; ++k) {
                out.image.channels[k](r, c) = double(src[std::size_t(c) * n_ch + k]);
            }
        }
    }
    return out;
}

}  // namespace detail
}  // namespace pinmask
