// The Cairo canvas of the drawn scenes (scene_letter.cpp, scene_text.cpp): an 8-bit alpha surface
// of rows x cols pixels, a drawing callback, and the ink coverage read back as a plane.
#pragma once

#include <cairo.h>

#include <functional>
#include <string>

#include "core/image/image.hpp"

namespace pinmask {

// Calls draw(cr) on a fresh rows x cols CAIRO_FORMAT_A8 surface (rows, cols >= 1: the caller
// checks) and returns the alpha per pixel / 255: 1 where ink covers the pixel, 0 where none does.
// RuntimeFailure "<what>: Cairo could not create ..." / "<what>: Cairo failed: ..." when Cairo
// does; exceptions from draw pass through.
Plane render_ink_coverage(int rows, int cols, const std::string& what,
                          const std::function<void(cairo_t*)>& draw);

}  // namespace pinmask
