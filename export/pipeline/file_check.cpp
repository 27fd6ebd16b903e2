#include "export/pipeline/file_check.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>

#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "export/formats/pdf_reader.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/shapes.hpp"
#include "export/pipeline/raster_check.hpp"

namespace pinmask {
namespace {

bool box_inside(const BoxNm& inner, const BoxNm& outer) {
    return inner.x0 >= outer.x0 && inner.y0 >= outer.y0 && inner.x1 <= outer.x1 &&
           inner.y1 <= outer.y1;
}

// Native circles as the polygons the design-rule check needs (auto sides, 199-vertex limit).
std::vector<Ring> circle_polygons(const std::vector<CircleNm>& circles, std::int64_t grid) {
    std::vector<Ring> out;
    for (const CircleNm& c : circles) {
        const double r = 0.5 * double(c.diameter_nm);
        const int sides = circle_sides(r, 0.0, kGdsFriendlyMaxVertices, grid);
        const std::int64_t m = c.diameter_nm + 2 * grid;
        const BoxNm cell{c.centre.x - m, c.centre.y - m, c.centre.x + m, c.centre.y + m};
        out.push_back(
            regular_polygon(double(c.centre.x), double(c.centre.y), r, sides, cell, grid));
    }
    return out;
}

}  // namespace

FileCheck check_file_geometry(const FileGeometry& file, const FileCheckOptions& o) {
    FileCheck c;
    c.max_xor_nm2 = o.max_xor_nm2;
    Layout& l = c.layout;
    const auto tone = file.info.find("tone");
    l.tone = tone == file.info.end() ? Tone::kClear : parse_tone(tone->second, "tone");
    std::int64_t grid = 1;
    if (auto g = file.info.find("grid_nm"); g != file.info.end())
        grid = std::max<std::int64_t>(1, std::atoll(g->second.c_str()));
    std::vector<Ring> rings = file.rings;
    const std::vector<Ring> from_circles = circle_polygons(file.circles, grid);
    l.extent = bounding_box(rings);
    if (!from_circles.empty()) l.extent = box_union(l.extent, bounding_box(from_circles));
    const auto hash = file.info.find("hash");
    const std::string file_hash = hash == file.info.end() ? "" : hash->second;
    if (o.design && o.whole_layout) {
        c.comparison = compare_with_layout(file, *o.design);
        if (c.comparison->identical()) {  // the file is the design: check the design itself
            l = *o.design;
            c.drc = run_drc(l, o.rules);
            return c;
        }
    }
    BoxNm outline =
        o.design ? bounding_box(o.design->polygons) : o.outline.value_or(bounding_box(rings));
    if (!o.design && !o.outline) outline = box_union(outline, l.extent);
    for (const Ring& r : rings)
        (box_inside(bounding_box({r}), outline) ? l.polygons : l.annotations).push_back(r);
    l.polygons.insert(l.polygons.end(), from_circles.begin(), from_circles.end());
    l.active_area = o.design ? o.design->active_area : outline;
    if (o.design) l.extent = box_union(l.extent, o.design->extent);
    if (o.design && !o.whole_layout)
        c.comparison =
            compare_rings(l.polygons, o.design->polygons, file_hash, o.design->mask_hash);
    c.drc = run_drc(l, o.rules);
    return c;
}

bool is_picture(FabFormat f) {
    return f == FabFormat::kPdf || f == FabFormat::kPng || f == FabFormat::kTiff1;
}

std::optional<FabFormat> picture_format_of(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".pdf") return FabFormat::kPdf;
    if (ext == ".png") return FabFormat::kPng;
    if (ext == ".tif" || ext == ".tiff") return FabFormat::kTiff1;
    return std::nullopt;
}

PictureComparison compare_picture(const std::filesystem::path& path, FabFormat format,
                                  const Layout& design, const PictureCheckOptions& o) {
    if (!is_picture(format))
        throw invalid_field("format", fab_format_name(format),
                            "is not a picture (pdf, png, tiff1)");
    if (format == FabFormat::kTiff1) {
        const RasterComparison r =
            compare_raster(read_tiff1_file(path), design, DrawMode::kFilm, 0);
        return {
            "1-bit pixels vs the design rasterised at pixel centres at the file's dpi "
            "(tolerance 0 pixels)",
            r.describe(), r.ok()};
    }
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw RuntimeFailure("cannot read " + path.string() + ": " + ec.message());
    check_memory(double(size) * 2.0, "reading " + path.string());
    std::ifstream in(path, std::ios::binary);
    std::string bytes(size, '\0');
    if (!in.read(bytes.data(), std::streamsize(size)))
        throw RuntimeFailure("cannot read " + path.string());
    try {
        if (format == FabFormat::kPng) {
            if (!(o.png_dpi > 0))
                throw invalid_field("png dpi", format_number(o.png_dpi),
                                    "is unknown: a PNG is checked with its export sidecar");
            const RasterComparison r =
                compare_raster(read_png_bytes(bytes, o.png_dpi), design, o.draw, kRasterEdgePixels);
            return {
                "grey pixels (black below half grey) vs the design rasterised at pixel "
                "centres, differences allowed within " +
                    std::to_string(kRasterEdgePixels) + " px of an edge",
                r.describe(), r.ok()};
        }
        PdfOptions po = o.pdf;
        po.draw = o.draw;
        const PdfComparison r = compare_pdf(read_pdf_page(bytes), design, po);
        return {"filled paths of the content stream vs the design's page, ring by ring",
                r.describe(), r.ok()};
    } catch (const InvalidInput& e) {
        throw InvalidInput(path.string() + ": " + e.what());
    }
}

std::string verify_picture(const std::filesystem::path& path, FabFormat format,
                           const Layout& design, const WriteOptions& w) {
    PictureCheckOptions o;
    o.draw = w.draw;
    o.png_dpi = w.png_dpi;
    o.pdf = w.pdf;
    const PictureComparison c = compare_picture(path, format, design, o);
    if (!c.ok)
        throw RuntimeFailure(fab_format_name(format) +
                             " file read back differs from the design: " + c.result);
    return "read back: " + c.result;
}

FileCheck check_picture_file(const std::filesystem::path& path, const Layout& design,
                             const PictureCheckOptions& o) {
    const std::optional<FabFormat> f = picture_format_of(path);
    if (!f)
        throw invalid_field("file", path.string(), "extension must be .pdf, .png, .tif or .tiff");
    protect_input(path);
    FileCheck c;
    const PictureComparison pc = compare_picture(path, *f, design, o);
    c.picture = pc;
    c.layout = design;
    c.drc = run_drc(c.layout, o.rules);
    return c;
}

}  // namespace pinmask
