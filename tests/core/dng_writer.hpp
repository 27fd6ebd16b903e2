// A minimal DNG writer for the RAW tests (libtiff): one 16-bit CFA plane, uncompressed, with
// the DNG tags LibRaw needs (DNGVersion, UniqueCameraModel, CFARepeatPatternDim, CFAPattern,
// BlackLevelRepeatDim, BlackLevel, WhiteLevel, ColorMatrix1). Written for tests/core only.
#pragma once

#include <tiffio.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace pinmask::test {

struct DngSpec {
    int rows = 24, cols = 28;                     // LibRaw (dcraw) refuses images under 22 x 22
    std::vector<std::uint16_t> values;            // rows * cols, row-major raw counts
    std::array<std::uint8_t, 4> cfa{0, 1, 1, 2};  // 2 x 2 pattern, 0 R, 1 G, 2 B: RGGB
    std::array<float, 4> black{64, 64, 64, 64};   // per position of the 2 x 2 repeat
    std::uint32_t white = 4095;
    std::string make = "pinmask", model = "test sensor";
};

inline void write_dng(const std::filesystem::path& path, const DngSpec& s) {
    TIFF* t = TIFFOpen(path.c_str(), "w");
    if (!t) throw std::runtime_error("cannot write " + path.string());
    TIFFSetField(t, TIFFTAG_SUBFILETYPE, 0);
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, s.cols);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, s.rows);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 16);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_NONE);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, 32803);  // CFA
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, s.rows);
    TIFFSetField(t, TIFFTAG_MAKE, s.make.c_str());
    TIFFSetField(t, TIFFTAG_MODEL, s.model.c_str());
    TIFFSetField(t, TIFFTAG_UNIQUECAMERAMODEL, "pinmask test sensor");
    const std::uint8_t version[4] = {1, 4, 0, 0};
    TIFFSetField(t, TIFFTAG_DNGVERSION, version);
    TIFFSetField(t, TIFFTAG_DNGBACKWARDVERSION, version);
    const std::uint16_t dim[2] = {2, 2};
    TIFFSetField(t, TIFFTAG_CFAREPEATPATTERNDIM, dim);
    TIFFSetField(t, TIFFTAG_CFAPATTERN, 4, s.cfa.data());
    TIFFSetField(t, TIFFTAG_BLACKLEVELREPEATDIM, dim);
    TIFFSetField(t, TIFFTAG_BLACKLEVEL, 4, s.black.data());
    TIFFSetField(t, TIFFTAG_WHITELEVEL, 1, &s.white);
    const float matrix[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    TIFFSetField(t, TIFFTAG_COLORMATRIX1, 9, matrix);
    TIFFSetField(t, TIFFTAG_CALIBRATIONILLUMINANT1, 21);  // D65
    std::vector<std::uint16_t> row(static_cast<std::size_t>(s.cols));
    for (int r = 0; r < s.rows; ++r) {
        for (int c = 0; c < s.cols; ++c)
            row[c] = s.values[static_cast<std::size_t>(r) * s.cols + c];
        if (TIFFWriteScanline(t, row.data(), r, 0) < 0) {
            TIFFClose(t);
            throw std::runtime_error("cannot write a row of " + path.string());
        }
    }
    TIFFClose(t);
}

}  // namespace pinmask::test
