// Owning handles for Cairo objects: one home for the deleters every drawing file needs.
// Header-only and nothing in core/ includes it, so core/ neither compiles against nor links
// Cairo; include it only from a library that links PkgConfig::CAIRO (export/layout/,
// export/formats/, report/, optimize/simulate/, decode/calibrate/, bench/ through export/). It
// lives here because core/ is the one folder all four depend on (decode/calibrate/ does not depend
// on export/, docs/design.md section 3).
#pragma once

#include <cairo.h>

#include <memory>

namespace pinmask::cairo {

struct SurfaceDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
    void operator()(cairo_t* c) const { cairo_destroy(c); }
};
struct FontOptionsDeleter {
    void operator()(cairo_font_options_t* o) const { cairo_font_options_destroy(o); }
};

using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;
using FontOptionsPtr = std::unique_ptr<cairo_font_options_t, FontOptionsDeleter>;

}  // namespace pinmask::cairo
