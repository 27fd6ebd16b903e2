#include "export/pipeline/raster_check.hpp"

#include <png.h>
#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <memory>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "export/formats/plotter_raster.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {
namespace {

constexpr double kCmPerInch = 2.54;

// libtiff's messages for the file being read go into this text, never to stderr.
int keep_error(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
    char buf[256];
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    auto* text = static_cast<std::string*>(user);
    if (text->size() < 1000) *text += std::string(text->empty() ? "" : "; ") + module + ": " + buf;
    return 1;
}
int drop_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

InvalidInput bad_file(const std::filesystem::path& path, const std::string& rule) {
    return InvalidInput(path.string() + ": " + rule);
}

void check_size(std::int64_t cols, std::int64_t rows, const std::string& what) {
    if (cols < 1 || rows < 1 || cols > kMaxRasterPixels || rows > kMaxRasterPixels)
        throw InvalidInput(what + ": " + std::to_string(cols) + " x " + std::to_string(rows) +
                           " pixels; must be 1.." + std::to_string(kMaxRasterPixels) + " a side");
    check_memory(double((cols + 7) / 8) * double(rows) * 3.0, what);
}

// Reference pixels: 1 = black (opaque in film mode, drawn in polygons mode).
PlotterRaster reference_pixels(const Layout& design, DrawMode draw, double dpi) {
    Layout l = design;
    if (draw == DrawMode::kPolygons) l.tone = Tone::kDark;  // drawn rings black, nothing else
    return plotter_raster(l, dpi);
}

// Rings narrower than 3 pixels in x or y (their pixels are all within one pixel of an edge).
std::size_t narrow_rings(const Layout& l, double dpi) {
    const double three_px = 3.0 * 25.4e6 / dpi;
    std::size_t n = 0;
    for (const auto* set : {&l.polygons, &l.annotations})
        for (const Ring& r : *set) {
            const BoxNm b = bounding_box({r});
            if (double(b.x1 - b.x0) < three_px || double(b.y1 - b.y0) < three_px) ++n;
        }
    return n;
}

}  // namespace

RasterPicture read_tiff1_file(const std::filesystem::path& path) {
    std::string errors;
    TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
    if (!opts) throw RuntimeFailure("libtiff: out of memory");
    TIFFOpenOptionsSetErrorHandlerExtR(opts, keep_error, &errors);
    TIFFOpenOptionsSetWarningHandlerExtR(opts, drop_warning, nullptr);
    TIFF* raw = TIFFOpenExt(path.c_str(), "r", opts);
    TIFFOpenOptionsFree(opts);
    if (!raw) throw bad_file(path, "not a readable TIFF (" + errors + ")");
    std::unique_ptr<TIFF, void (*)(TIFF*)> tif(raw, [](TIFF* t) { TIFFClose(t); });
    std::uint32_t w = 0, h = 0;
    std::uint16_t bps = 0, spp = 1, photometric = 0, unit = RESUNIT_INCH;
    float xres = 0, yres = 0;
    TIFFGetField(raw, TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(raw, TIFFTAG_IMAGELENGTH, &h);
    TIFFGetFieldDefaulted(raw, TIFFTAG_BITSPERSAMPLE, &bps);
    TIFFGetFieldDefaulted(raw, TIFFTAG_SAMPLESPERPIXEL, &spp);
    if (bps != 1 || spp != 1)
        throw bad_file(path, "is not a 1-bit TIFF (" + std::to_string(spp) + " samples of " +
                                 std::to_string(bps) + " bits)");
    if (!TIFFGetField(raw, TIFFTAG_PHOTOMETRIC, &photometric) ||
        (photometric != PHOTOMETRIC_MINISWHITE && photometric != PHOTOMETRIC_MINISBLACK))
        throw bad_file(path, "1-bit TIFF without MinIsWhite/MinIsBlack photometric");
    if (!TIFFGetField(raw, TIFFTAG_XRESOLUTION, &xres) ||
        !TIFFGetField(raw, TIFFTAG_YRESOLUTION, &yres))
        throw bad_file(path, "has no resolution tags: its physical size is unknown");
    TIFFGetFieldDefaulted(raw, TIFFTAG_RESOLUTIONUNIT, &unit);
    if (unit != RESUNIT_INCH && unit != RESUNIT_CENTIMETER)
        throw bad_file(path, "resolution unit is neither inch nor centimetre");
    if (!(xres > 0) || xres != yres)
        throw bad_file(path, "x and y resolution must be equal and positive (" +
                                 std::to_string(xres) + ", " + std::to_string(yres) + ")");
    RasterPicture p;
    p.cols = w;
    p.rows = h;
    p.dpi = unit == RESUNIT_INCH ? double(xres) : double(xres) * kCmPerInch;
    check_size(p.cols, p.rows, path.string());
    const char* description = nullptr;
    if (TIFFGetField(raw, TIFFTAG_IMAGEDESCRIPTION, &description) && description)
        p.info = parse_info(description);
    const std::size_t stride = p.stride();
    p.bits.assign(stride * std::size_t(p.rows), 0);
    std::vector<std::uint8_t> row(std::size_t(std::max<tmsize_t>(TIFFScanlineSize(raw), 0)));
    if (row.size() < stride) throw bad_file(path, "scanline too short");
    std::uint16_t fill = FILLORDER_MSB2LSB;
    TIFFGetFieldDefaulted(raw, TIFFTAG_FILLORDER, &fill);
    const bool invert = photometric == PHOTOMETRIC_MINISBLACK;  // there 1 = white
    const std::uint8_t pad =
        p.cols % 8 ? std::uint8_t(0xFF << (8 - p.cols % 8)) : std::uint8_t(0xFF);
    for (std::int64_t i = 0; i < p.rows; ++i) {
        if (TIFFReadScanline(raw, row.data(), std::uint32_t(i), 0) < 0)
            throw bad_file(path, "row " + std::to_string(i) + " unreadable (" + errors + ")");
        std::uint8_t* out = p.bits.data() + std::size_t(i) * stride;
        for (std::size_t k = 0; k < stride; ++k) out[k] = invert ? std::uint8_t(~row[k]) : row[k];
        out[stride - 1] &= pad;
    }
    (void)fill;  // libtiff returns the rows MSB first whatever the FillOrder tag
    return p;
}

RasterPicture read_png_bytes(std::string_view bytes, double dpi) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
        throw InvalidInput(std::string("png: ") + image.message);
    std::unique_ptr<png_image, void (*)(png_image*)> guard(&image, png_image_free);
    RasterPicture p;
    p.cols = image.width;
    p.rows = image.height;
    p.dpi = dpi;
    check_size(p.cols, p.rows, "png");
    check_memory(double(p.cols) * double(p.rows) * 2.0, "png grey pixels");
    image.format = PNG_FORMAT_GRAY;
    std::vector<std::uint8_t> grey(std::size_t(p.cols) * std::size_t(p.rows));
    if (!png_image_finish_read(&image, nullptr, grey.data(), 0, nullptr))
        throw InvalidInput(std::string("png: ") + image.message);
    p.bits.assign(p.stride() * std::size_t(p.rows), 0);
    for (std::int64_t i = 0; i < p.rows; ++i)
        for (std::int64_t j = 0; j < p.cols; ++j)
            if (grey[std::size_t(i) * std::size_t(p.cols) + std::size_t(j)] < kPngBlackBelow)
                p.bits[std::size_t(i) * p.stride() + std::size_t(j / 8)] |=
                    std::uint8_t(0x80 >> (j % 8));
    return p;
}

std::string RasterComparison::describe() const {
    char buf[400];
    if (!same_size()) {
        std::snprintf(buf, sizeof buf,
                      "%lld x %lld pixels, the design at %.6g dpi is %lld x %lld: wrong size",
                      (long long)cols, (long long)rows, dpi, (long long)expected_cols,
                      (long long)expected_rows);
        return buf;
    }
    std::snprintf(buf, sizeof buf,
                  "%lld x %lld pixels at %.6g dpi: %zu differ from the design rasterised at "
                  "pixel centres, %zu of them more than %d px from an edge (allowed: 0)",
                  (long long)cols, (long long)rows, dpi, differing, beyond_edges,
                  edge_tolerance_px);
    std::string s = buf;
    if (unresolved > 0)
        s += "; " + std::to_string(unresolved) +
             " drawn rings are narrower than 3 px and not resolved by this check";
    return s;
}

RasterComparison compare_raster(const RasterPicture& pic, const Layout& design, DrawMode draw,
                                int edge_tolerance_px) {
    if (!(pic.dpi >= 1 && pic.dpi <= 1e6))
        throw invalid_field("dpi", format_number(pic.dpi), "must be in 1..1000000");
    if (edge_tolerance_px < 0 || edge_tolerance_px > 8)
        throw invalid_field("edge tolerance", std::to_string(edge_tolerance_px),
                            "must be in 0..8 pixels");
    RasterComparison c;
    c.cols = pic.cols;
    c.rows = pic.rows;
    c.dpi = pic.dpi;
    c.edge_tolerance_px = edge_tolerance_px;
    const PlotterRaster ref = reference_pixels(design, draw, pic.dpi);
    c.expected_cols = ref.cols;
    c.expected_rows = ref.rows;
    if (!c.same_size()) return c;
    if (edge_tolerance_px > 0) c.unresolved = narrow_rings(design, pic.dpi);
    const std::int64_t W = c.cols, H = c.rows, t = edge_tolerance_px;
    auto at = [&](std::int64_t i, std::int64_t j) { return ref.opaque(i, j); };
    const std::size_t stride = pic.stride();
    for (std::int64_t i = 0; i < H; ++i)
        for (std::int64_t j = 0; j < W; ++j) {
            if (j % 8 == 0 && pic.bits[std::size_t(i) * stride + std::size_t(j / 8)] ==
                                  ref.bits[std::size_t(i) * stride + std::size_t(j / 8)]) {
                j += 7;  // the whole byte agrees (padding bits are 0 in both)
                continue;
            }
            const bool want = at(i, j);
            if (pic.at(i, j) == want) continue;
            ++c.differing;
            bool near_edge = false;
            for (std::int64_t di = -t; di <= t && !near_edge; ++di)
                for (std::int64_t dj = -t; dj <= t && !near_edge; ++dj) {
                    const std::int64_t a = i + di, b = j + dj;
                    // Beyond the picture the film ends: an edge too.
                    near_edge = a < 0 || b < 0 || a >= H || b >= W || at(a, b) != want;
                }
            if (!near_edge) ++c.beyond_edges;
        }
    return c;
}

}  // namespace pinmask
