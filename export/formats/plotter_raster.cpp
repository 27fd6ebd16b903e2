#include "export/formats/plotter_raster.hpp"

#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/shapes.hpp"

namespace pinmask {
namespace {

constexpr double kNmPerInch = 25.4e6;

struct Grid {
    double pixel = 0;  // nm
    std::int64_t cols = 0, rows = 0;
    BoxNm e;
};

Grid grid_of(const Layout& l, double dpi) {
    if (!(dpi >= 1 && dpi <= 1e6))
        throw invalid_field(field_ref("tiff_dpi"), format_number(dpi), "must be in 1..1000000");
    Grid g;
    g.pixel = kNmPerInch / dpi;
    g.e = l.extent;
    const double w = std::ceil(double(g.e.x1 - g.e.x0) / g.pixel - 1e-9);
    const double h = std::ceil(double(g.e.y1 - g.e.y0) / g.pixel - 1e-9);
    if (std::max(w, h) > double(kMaxRasterPixels))
        throw invalid_field(field_ref("tiff_dpi"), format_number(dpi),
                            "gives a raster of " + std::to_string(std::llround(w)) + " x " +
                                std::to_string(std::llround(h)) + " pixels, more than " +
                                std::to_string(kMaxRasterPixels) + " a side");
    g.cols = std::max<std::int64_t>(1, std::int64_t(w));
    g.rows = std::max<std::int64_t>(1, std::int64_t(h));
    return g;
}

// First pixel index whose centre is at or beyond coordinate v (pixels from origin o).
std::int64_t first_centre_at_or_after(double v, double o, double pixel) {
    return std::int64_t(std::ceil((v - o) / pixel - 0.5));
}

// Pixels whose centre x (or y measured downwards from the top) lies in the span.
void fill_ring(PlotterRaster& r, const Grid& g, const Ring& ring, bool opaque) {
    const std::size_t stride = std::size_t((r.cols + 7) / 8);
    const BoxNm b = bounding_box({ring});
    // Rows: centre y_c = e.y1 - (i + 0.5) p; y_c in [b.y0, b.y1] -> i range.
    const std::int64_t i0 = std::max<std::int64_t>(
        0, std::int64_t(std::floor((double(g.e.y1 - b.y1)) / g.pixel - 0.5)));
    const std::int64_t i1 = std::min<std::int64_t>(
        r.rows - 1, std::int64_t(std::ceil((double(g.e.y1 - b.y0)) / g.pixel - 0.5)));
    std::vector<double> xs;
    for (std::int64_t i = i0; i <= i1; ++i) {
        const double yc = double(g.e.y1) - (double(i) + 0.5) * g.pixel;
        xs.clear();
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const PointNm& a = ring[k];
            const PointNm& c = ring[(k + 1) % ring.size()];
            // Half-open in y: an edge counts when yc is in [min y, max y).
            const double ya = double(a.y), yb = double(c.y);
            if ((ya <= yc && yc < yb) || (yb <= yc && yc < ya))
                xs.push_back(double(a.x) + (yc - ya) * double(c.x - a.x) / (yb - ya));
        }
        std::sort(xs.begin(), xs.end());
        for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
            // Columns whose centre x_c = e.x0 + (j + 0.5) p is in [xs[k], xs[k+1]).
            const std::int64_t j0 =
                std::max<std::int64_t>(0, first_centre_at_or_after(xs[k], double(g.e.x0), g.pixel));
            const std::int64_t j1 = std::min<std::int64_t>(
                r.cols, first_centre_at_or_after(xs[k + 1], double(g.e.x0), g.pixel));
            std::uint8_t* row = r.bits.data() + std::size_t(i) * stride;
            for (std::int64_t j = j0; j < j1; ++j) {
                const std::uint8_t m = std::uint8_t(0x80 >> (j % 8));
                if (opaque)
                    row[j / 8] |= m;
                else
                    row[j / 8] &= std::uint8_t(~m);
            }
        }
    }
}

// libtiff output into a std::string.
struct MemoryFile {
    std::string data;
    toff_t pos = 0;
};

tsize_t mem_read(thandle_t, tdata_t, tsize_t) { return 0; }
tsize_t mem_write(thandle_t h, tdata_t buf, tsize_t n) {
    auto* f = static_cast<MemoryFile*>(h);
    if (f->pos + toff_t(n) > f->data.size()) f->data.resize(std::size_t(f->pos + n));
    std::memcpy(f->data.data() + f->pos, buf, std::size_t(n));
    f->pos += toff_t(n);
    return n;
}
toff_t mem_seek(thandle_t h, toff_t off, int whence) {
    auto* f = static_cast<MemoryFile*>(h);
    if (whence == SEEK_SET) f->pos = off;
    if (whence == SEEK_CUR) f->pos += off;
    if (whence == SEEK_END) f->pos = f->data.size() + off;
    return f->pos;
}
int mem_close(thandle_t) { return 0; }
toff_t mem_size(thandle_t h) { return static_cast<MemoryFile*>(h)->data.size(); }
int mem_map(thandle_t, tdata_t*, toff_t*) { return 0; }
void mem_unmap(thandle_t, tdata_t, toff_t) {}

}  // namespace

SnapReport plotter_snap_report(const Layout& l, double dpi) {
    const Grid g = grid_of(l, dpi);
    SnapReport s;
    s.pixel_nm = g.pixel;
    s.cols = g.cols;
    s.rows = g.rows;
    for (const Ring& ring : l.polygons) {
        const BoxNm b = bounding_box({ring});
        // x: pixels with centres in [x0, x1); y (rows counted from the top): centres in
        // (y0, y1], i.e. e.y1 - y in [e.y1 - y1, e.y1 - y0).
        const double ox = double(g.e.x0), oy = double(g.e.y1);
        const double lx = double(first_centre_at_or_after(double(b.x0), ox, g.pixel)) * g.pixel;
        const double rx = double(first_centre_at_or_after(double(b.x1), ox, g.pixel)) * g.pixel;
        const double ty = double(first_centre_at_or_after(oy - double(b.y1), 0, g.pixel)) * g.pixel;
        const double by = double(first_centre_at_or_after(oy - double(b.y0), 0, g.pixel)) * g.pixel;
        const double wx = double(b.x1 - b.x0), wy = double(b.y1 - b.y0);
        s.max_size_error_nm =
            std::max({s.max_size_error_nm, std::fabs((rx - lx) - wx), std::fabs((by - ty) - wy)});
        const double cx = 0.5 * (lx + rx) + ox - 0.5 * double(b.x0 + b.x1);
        const double cy = (oy - 0.5 * (ty + by)) - 0.5 * double(b.y0 + b.y1);
        s.max_position_error_nm = std::max({s.max_position_error_nm, std::fabs(cx), std::fabs(cy)});
        ++s.polygons;
    }
    return s;
}

PlotterRaster plotter_raster(const Layout& l, double dpi) {
    const Grid g = grid_of(l, dpi);
    PlotterRaster r;
    r.cols = g.cols;
    r.rows = g.rows;
    const double bytes = double((g.cols + 7) / 8) * double(g.rows);
    check_memory(bytes * 2.0, "1-bit plotter raster");
    const bool clear = l.tone == Tone::kClear;
    // Clear tone: the film is opaque where nothing is drawn; dark tone: clear.
    r.bits.assign(std::size_t(bytes), clear ? 0xFF : 0x00);
    for (const auto* set : {&l.polygons, &l.annotations})
        for (const Ring& ring : *set) fill_ring(r, g, ring, !clear);
    // Padding bits past the last column stay 0 (white) in every row.
    if (r.cols % 8) {
        const std::size_t stride = std::size_t((r.cols + 7) / 8);
        const std::uint8_t keep = std::uint8_t(0xFF << (8 - r.cols % 8));
        for (std::int64_t i = 0; i < r.rows; ++i)
            r.bits[std::size_t(i) * stride + stride - 1] &= keep;
    }
    return r;
}

std::string plotter_tiff(const Layout& l, double dpi, double max_snap_error_nm) {
    const SnapReport s = plotter_snap_report(l, dpi);
    const double worst = std::max(s.max_size_error_nm, s.max_position_error_nm);
    if (max_snap_error_nm > 0 && worst > max_snap_error_nm)
        throw invalid_field(field_ref("max_snap_error_nm"), nm_text(max_snap_error_nm),
                            "is exceeded at " + std::to_string(dpi) + " dpi: snapping to the " +
                                nm_text(s.pixel_nm) + " address grid changes a pinhole's size by " +
                                nm_text(s.max_size_error_nm) + " and its centre by " +
                                nm_text(s.max_position_error_nm) + "; raise " +
                                field_ref("tiff_dpi"));
    const PlotterRaster r = plotter_raster(l, dpi);
    MemoryFile file;
    TIFF* raw = TIFFClientOpen("pinmask.tif", "w", &file, mem_read, mem_write, mem_seek, mem_close,
                               mem_size, mem_map, mem_unmap);
    if (!raw) throw RuntimeFailure("libtiff: cannot open a memory TIFF");
    std::unique_ptr<TIFF, void (*)(TIFF*)> tif(raw, [](TIFF* t) { TIFFClose(t); });
    const std::string description = "pinmask 1-bit plotter raster " + layout_info(l, "px") +
                                    " dpi=" + std::to_string(std::llround(dpi));
    TIFFSetField(raw, TIFFTAG_IMAGEWIDTH, std::uint32_t(r.cols));
    TIFFSetField(raw, TIFFTAG_IMAGELENGTH, std::uint32_t(r.rows));
    TIFFSetField(raw, TIFFTAG_BITSPERSAMPLE, 1);
    TIFFSetField(raw, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(raw, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISWHITE);
    TIFFSetField(raw, TIFFTAG_COMPRESSION, COMPRESSION_PACKBITS);
    TIFFSetField(raw, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(raw, TIFFTAG_FILLORDER, FILLORDER_MSB2LSB);
    TIFFSetField(raw, TIFFTAG_ROWSPERSTRIP, 64);
    TIFFSetField(raw, TIFFTAG_XRESOLUTION, dpi);
    TIFFSetField(raw, TIFFTAG_YRESOLUTION, dpi);
    TIFFSetField(raw, TIFFTAG_RESOLUTIONUNIT, RESUNIT_INCH);
    TIFFSetField(raw, TIFFTAG_IMAGEDESCRIPTION, description.c_str());
    const std::size_t stride = std::size_t((r.cols + 7) / 8);
    std::vector<std::uint8_t> row(stride);
    for (std::int64_t i = 0; i < r.rows; ++i) {
        std::memcpy(row.data(), r.bits.data() + std::size_t(i) * stride, stride);
        if (TIFFWriteScanline(raw, row.data(), std::uint32_t(i), 0) < 0)
            throw RuntimeFailure("libtiff: cannot write row " + std::to_string(i));
    }
    tif.reset();
    return std::move(file.data);
}

}  // namespace pinmask
