#include "optimize/simulate/scene_cairo.hpp"

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"

namespace pinmask {

Plane render_ink_coverage(int rows, int cols, const std::string& what,
                          const std::function<void(cairo_t*)>& draw) {
    cairo::SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_A8, cols, rows));
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure(what + ": Cairo could not create a " + std::to_string(cols) + " x " +
                             std::to_string(rows) + " surface");
    }
    cairo::ContextPtr cr(cairo_create(surface.get()));
    draw(cr.get());
    cairo_surface_flush(surface.get());
    if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS) {
        throw RuntimeFailure(what +
                             ": Cairo failed: " + cairo_status_to_string(cairo_status(cr.get())));
    }
    const unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    Plane p(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) p(r, c) = data[r * stride + c] / 255.0;
    return p;
}

}  // namespace pinmask
