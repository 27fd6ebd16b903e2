// 1-bit raster of a layout for laser film plotters (`--format tiff1 --dpi`): the film as it is
// exposed, black = opaque, white = clear (tone and mirroring as in the layout), one bit per
// plotter address. A pixel is clear or opaque by its centre: it takes the drawn colour when its
// centre lies inside a drawn ring (even-odd over the ring's edges, half-open so that shared
// edges are drawn once). So every polygon edge moves to the nearest address-grid line: a
// pinhole of side s spanning [x0, x1) becomes the pixels whose centres fall in it, and its size
// and centre change by at most one pixel and half a pixel. The snapping report gives the worst
// of those changes over all drawn polygons (from their bounding boxes, exact for the squares,
// the bounding extent for other shapes), and the export is refused when it exceeds the
// tolerance. The TIFF: one strip group of 1-bit rows, PhotometricInterpretation MinIsWhite (1 =
// black), PackBits compression, XResolution = YResolution = dpi with ResolutionUnit inch (so the
// physical size is pixels / dpi), the info tokens in ImageDescription, no date: deterministic.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "export/layout/layout.hpp"

namespace pinmask {

// Largest raster side in pixels (2^20): 26.2 mm at 1 um addressing... and the memory budget.
inline constexpr std::int64_t kMaxRasterPixels = std::int64_t{1} << 20;

struct SnapReport {
    double pixel_nm = 0.0;               // the address pitch, 25.4e6 / dpi nm
    std::int64_t cols = 0, rows = 0;     // raster size
    double max_size_error_nm = 0.0;      // worst |snapped width - drawn width| (x or y)
    double max_position_error_nm = 0.0;  // worst |snapped centre - drawn centre|
    std::size_t polygons = 0;            // polygons measured
};

// The raster geometry and snapping of `layout` at `dpi` (no pixels are made). Throws
// InvalidInput naming `tiff_dpi` for a dpi out of 1..1e6 or a raster beyond kMaxRasterPixels a
// side.
SnapReport plotter_snap_report(const Layout& layout, double dpi);

struct PlotterRaster {
    std::int64_t cols = 0, rows = 0;
    std::vector<std::uint8_t> bits;  // rows of ceil(cols / 8) bytes, MSB first, 1 = opaque
    bool opaque(std::int64_t row, std::int64_t col) const {
        return bits[std::size_t(row) * std::size_t((cols + 7) / 8) + std::size_t(col / 8)] &
               (0x80 >> (col % 8));
    }
};

// The pixels (row 0 at the top of the extent). Charges the memory budget first.
PlotterRaster plotter_raster(const Layout& layout, double dpi);

// The TIFF file's bytes. Throws InvalidInput naming --max-snap-error when the report's size or
// position error exceeds max_snap_error_nm (> 0).
std::string plotter_tiff(const Layout& layout, double dpi, double max_snap_error_nm);

}  // namespace pinmask
