// PNG preview of a layout as the film looks (export/layout/film_paint: black opaque, white clear),
// covering the layout's extent at a chosen resolution, rendered by Cairo (antialiased edges) and
// encoded by Cairo's PNG writer (24-bit RGB; Cairo writes no physical-size chunk, the dpi is in
// the sidecar). Deterministic: the same layout and dpi give the same bytes.
#pragma once

#include <string>

#include "export/layout/film_paint.hpp"
#include "export/layout/layout.hpp"

namespace pinmask {

// Largest preview side in pixels (Cairo's image surface limit).
inline constexpr int kMaxPreviewPixels = 32767;

// Width and height in pixels of the preview at `dpi`: ceil(extent in inches * dpi), >= 1.
// Throws InvalidInput for dpi not positive and finite or a side above kMaxPreviewPixels, and
// ResourceLimit when the image would exceed the memory bound.
struct PreviewSize {
    int cols = 0;
    int rows = 0;
};
PreviewSize preview_size(const Layout& layout, double dpi);

// The PNG file bytes.
std::string png_preview(const Layout& layout, double dpi, DrawMode draw = DrawMode::kFilm);

}  // namespace pinmask
