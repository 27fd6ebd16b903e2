// Test-only JPEG encoder over libjpeg's compressor (pinmask has no JPEG writer: JPEG is lossy):
// writes 8-bit grey, RGB or CMYK samples as a baseline, progressive or arithmetic-coded JPEG in
// memory, with 4:4:4 or libjpeg's default 4:2:0 chroma sampling. libjpeg's default error manager
// is kept: the inputs are known to be valid, and a libjpeg error exits the test program (a
// failure). Also the byte patches the hostile-input tests apply to such a file.
#pragma once

// clang-format off
#include <cstdio>  // before jpeglib.h, which uses FILE and size_t without including them
#include <jpeglib.h>
// clang-format on

#include <cstdlib>
#include <string>
#include <vector>

namespace pinmask::test {

struct JpegSpec {
    int quality = 100;
    bool progressive = false;
    bool arithmetic = false;  // arithmetic instead of Huffman entropy coding
    bool subsample = false;   // libjpeg's default 2 x 2 chroma subsampling (4:2:0), else 4:4:4
    J_COLOR_SPACE input = JCS_RGB;      // JCS_GRAYSCALE, JCS_RGB or JCS_CMYK samples
    J_COLOR_SPACE file = JCS_UNKNOWN;   // colour space in the file; UNKNOWN: libjpeg's default
    std::vector<jpeg_scan_info> scans;  // a progressive scan script (overrides progressive)
};

// A valid progressive script for one component with 1 + 63 spectral bands and `refinements`
// successive-approximation steps each (Al from `refinements` down to 0): 64 (refinements + 1)
// scans.
inline std::vector<jpeg_scan_info> single_band_script(int refinements) {
    std::vector<jpeg_scan_info> scans;
    for (int band = 0; band < 64; ++band) {
        for (int ah = 0, al = refinements; al >= 0; ah = al, --al) {
            jpeg_scan_info s{};
            s.comps_in_scan = 1;
            s.component_index[0] = 0;
            s.Ss = s.Se = band;
            s.Ah = ah;
            s.Al = al;
            scans.push_back(s);
        }
    }
    return scans;
}

// `samples`: rows x cols x components, interleaved, row-major (components from spec.input).
inline std::string encode_jpeg(const std::vector<unsigned char>& samples, int rows, int cols,
                               const JpegSpec& spec) {
    jpeg_compress_struct c;
    jpeg_error_mgr err;
    c.err = jpeg_std_error(&err);
    jpeg_create_compress(&c);
    unsigned char* buf = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&c, &buf, &size);
    c.image_width = JDIMENSION(cols);
    c.image_height = JDIMENSION(rows);
    c.in_color_space = spec.input;
    c.input_components = spec.input == JCS_GRAYSCALE ? 1 : spec.input == JCS_CMYK ? 4 : 3;
    jpeg_set_defaults(&c);
    if (spec.file != JCS_UNKNOWN) jpeg_set_colorspace(&c, spec.file);
    jpeg_set_quality(&c, spec.quality, TRUE);
    c.dct_method = JDCT_ISLOW;
    c.arith_code = spec.arithmetic ? TRUE : FALSE;
    if (!spec.subsample) {
        for (int k = 0; k < c.num_components; ++k) {
            c.comp_info[k].h_samp_factor = 1;
            c.comp_info[k].v_samp_factor = 1;
        }
    }
    if (spec.progressive) jpeg_simple_progression(&c);
    if (!spec.scans.empty()) {
        c.scan_info = spec.scans.data();
        c.num_scans = int(spec.scans.size());
    }
    jpeg_start_compress(&c, TRUE);
    const std::size_t stride = std::size_t(cols) * c.input_components;
    while (c.next_scanline < c.image_height) {
        JSAMPROW row = const_cast<unsigned char*>(samples.data()) + c.next_scanline * stride;
        jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    std::string out(reinterpret_cast<const char*>(buf), size);
    std::free(buf);
    return out;
}

// Offset of the first frame header (SOF0..SOF2 marker FF C0/C1/C2) in `jpeg`, or npos. Its
// segment: marker (2), length (2), precision (1), height (2), width (2), components...
inline std::size_t sof_offset(const std::string& jpeg) {
    for (std::size_t i = 2; i + 1 < jpeg.size(); ++i) {
        const auto m = static_cast<unsigned char>(jpeg[i + 1]);
        if (static_cast<unsigned char>(jpeg[i]) == 0xff && (m == 0xc0 || m == 0xc1 || m == 0xc2)) {
            return i;
        }
    }
    return std::string::npos;
}

// Offset just past the first start-of-scan segment (FF DA): where the entropy-coded data begins.
inline std::size_t scan_data_offset(const std::string& jpeg) {
    for (std::size_t i = 2; i + 3 < jpeg.size(); ++i) {
        if (static_cast<unsigned char>(jpeg[i]) == 0xff &&
            static_cast<unsigned char>(jpeg[i + 1]) == 0xda) {
            const std::size_t len = (std::size_t(static_cast<unsigned char>(jpeg[i + 2])) << 8) |
                                    static_cast<unsigned char>(jpeg[i + 3]);
            return i + 2 + len;
        }
    }
    return std::string::npos;
}

}  // namespace pinmask::test
