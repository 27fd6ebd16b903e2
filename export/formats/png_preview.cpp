#include "export/formats/png_preview.hpp"

#include <cairo.h>

#include <cmath>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "export/layout/film_paint.hpp"

namespace pinmask {
namespace {

constexpr double kNmPerInch = 25.4e6;

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

}  // namespace

PreviewSize preview_size(const Layout& layout, double dpi) {
    if (!(dpi > 0) || !std::isfinite(dpi))
        throw invalid_field("dpi", format_number(dpi), "must be positive and finite");
    const BoxNm& e = layout.extent;
    const double w = std::ceil(double(e.x1 - e.x0) / kNmPerInch * dpi - 1e-9);
    const double h = std::ceil(double(e.y1 - e.y0) / kNmPerInch * dpi - 1e-9);
    if (std::max(w, h) > kMaxPreviewPixels)
        throw invalid_field("dpi", format_number(dpi),
                            "gives a preview of " + std::to_string(std::llround(w)) + " x " +
                                std::to_string(std::llround(h)) + " pixels, more than " +
                                std::to_string(kMaxPreviewPixels) + " per side; lower the dpi");
    check_memory(std::max(w, 1.0) * std::max(h, 1.0) * 4.0 * 2.0, "PNG preview");
    return {std::max(1, int(w)), std::max(1, int(h))};
}

std::string png_preview(const Layout& layout, double dpi, DrawMode draw) {
    const PreviewSize size = preview_size(layout, dpi);
    cairo::SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, size.cols, size.rows));
    check_cairo_surface(surface.get(), "PNG preview surface");
    cairo::ContextPtr cr(cairo_create(surface.get()));
    cairo_set_source_rgb(cr.get(), 1, 1, 1);
    cairo_paint(cr.get());
    // Pixels per nm; y flipped so the layout's y axis points up in the picture.
    const double s = dpi / kNmPerInch;
    cairo_scale(cr.get(), s, -s);
    cairo_translate(cr.get(), -double(layout.extent.x0), -double(layout.extent.y1));
    paint_film(cr.get(), layout, draw);
    check_cairo(cr.get(), "PNG preview");
    cr.reset();
    cairo_surface_flush(surface.get());
    std::string out;
    const cairo_status_t st = cairo_surface_write_to_png_stream(surface.get(), append, &out);
    if (st != CAIRO_STATUS_SUCCESS)
        throw RuntimeFailure(std::string("PNG preview: cairo: ") + cairo_status_to_string(st));
    return out;
}

}  // namespace pinmask
