// Reading back the raster pictures export writes (the 1-bit plotter TIFF, the PNG preview) and
// comparing them with their design, for `pinmask check`.
// The reference is the design rasterised at the file's resolution by export/formats/plotter_raster
// (a pixel is opaque or clear by its centre), in the picture's draw mode (film: the film as it
// looks; polygons: the drawn rings black on white, i.e. the layout rasterised as dark tone).
//   1-bit TIFF: written by that same rasteriser, so every pixel must agree (tolerance 0 pixels):
//     the check proves the file on disk is the design at its dpi (size, tone, mirroring, marks,
//     label, every pinhole), not an independent rendering.
//   PNG preview: drawn by Cairo with antialiasing (coverage, not centre sampling), read as grey
//     and thresholded at half grey. A pixel may then differ from the reference only where the
//     reference changes colour within kRasterEdgePixels pixels (an edge crosses the pixel or its
//     neighbour); any other differing pixel is a mismatch. Features narrower than three pixels
//     are all edge, so the PNG's dpi must resolve the pinholes for the check to see them: the
//     check reports how many reference features are that narrow (unresolved).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "export/layout/film_paint.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

// A pixel of the PNG may differ from the centre-sampled reference when the reference changes
// colour within this many pixels (Chebyshev distance) of it.
inline constexpr int kRasterEdgePixels = 1;
// Half grey: PNG pixels darker than this are opaque (black).
inline constexpr int kPngBlackBelow = 128;

// Pixels packed as export/formats/plotter_raster's: rows of ceil(cols / 8) bytes, MSB first, 1 =
// black (opaque), padding bits 0, row 0 at the top.
struct RasterPicture {
    std::int64_t cols = 0, rows = 0;
    std::vector<std::uint8_t> bits;
    double dpi = 0.0;                         // from the file's resolution tags (0: none)
    std::map<std::string, std::string> info;  // the TIFF's ImageDescription tokens
    std::size_t stride() const { return std::size_t((cols + 7) / 8); }
    bool at(std::int64_t row, std::int64_t col) const {
        return bits[std::size_t(row) * stride() + std::size_t(col / 8)] & (0x80 >> (col % 8));
    }
};

// A 1-bit TIFF as pinmask writes it (1 sample, 1 bit, MinIsWhite or MinIsBlack, resolution in
// inches or centimetres, equal in x and y). Throws InvalidInput naming the file otherwise.
RasterPicture read_tiff1_file(const std::filesystem::path& path);

// A PNG (any colour type; converted to grey, black below kPngBlackBelow). No resolution: the
// caller gives the dpi it was written at (the export sidecar).
RasterPicture read_png_bytes(std::string_view bytes, double dpi);

struct RasterComparison {
    std::int64_t cols = 0, rows = 0;                    // the picture's size
    std::int64_t expected_cols = 0, expected_rows = 0;  // the reference's at the same dpi
    double dpi = 0.0;
    int edge_tolerance_px = 0;     // 0 (TIFF) or kRasterEdgePixels (PNG)
    std::size_t differing = 0;     // pixels that differ from the reference
    std::size_t beyond_edges = 0;  // of those, further than the tolerance from an edge
    std::size_t unresolved = 0;    // drawn rings narrower than 3 pixels (PNG only)
    bool same_size() const { return cols == expected_cols && rows == expected_rows; }
    bool ok() const { return same_size() && beyond_edges == 0; }
    std::string describe() const;
};

// Compares the picture with `design` rasterised at picture.dpi in `draw` mode, allowing
// differences within edge_tolerance_px pixels of an edge of the reference.
RasterComparison compare_raster(const RasterPicture& picture, const Layout& design, DrawMode draw,
                                int edge_tolerance_px);

}  // namespace pinmask
