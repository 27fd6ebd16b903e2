// Drawing primitives of the comparison report (report/report.hpp), shared by its page layouts.
// User space is points with y down; text is Cairo's toy API, family "sans-serif", with hinting
// switched off so text extents (and therefore every layout decision) are the same on PDF, SVG
// and image surfaces.
#pragma once

#include <cairo.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask::report_draw {

struct Font {
    double size = 9.0;  // points
    bool bold = false;
    bool italic = false;
};

struct Box {
    double x = 0.0, y = 0.0, w = 0.0, h = 0.0;
};

// Ink of text and rules: a dark grey (never pure black), so pure black pixels on a page come
// from panel images only.
inline constexpr double kInk = 0.12;
inline constexpr double kRuleGrey = 0.6;

// Sets the font options used everywhere (no hinting, grey antialiasing) and the ink colour.
void prepare_context(cairo_t* cr);

// A context on a 1 x 1 image surface with prepare_context applied, for measuring text.
class Measure {
  public:
    Measure();
    ~Measure();
    Measure(const Measure&) = delete;
    Measure& operator=(const Measure&) = delete;
    cairo_t* cr() const { return cr_; }

  private:
    cairo_surface_t* surface_;
    cairo_t* cr_;
};

// Advance width of s in points.
double text_width(cairo_t* cr, const std::string& s, const Font& font);

// Draws s with its baseline at y; align 0 puts x at the left edge, 0.5 centre, 1 right edge.
void draw_text(cairo_t* cr, double x, double y, const std::string& s, const Font& font,
               double align = 0.0);

// s shortened with a trailing "..." so it is at most max_width wide (s itself when it fits).
std::string fit_text(cairo_t* cr, const std::string& s, const Font& font, double max_width);

// s broken at spaces into lines at most max_width wide (a word wider than that is cut by
// fit_text); an empty s gives one empty line.
std::vector<std::string> wrap_text(cairo_t* cr, const std::string& s, const Font& font,
                                   double max_width);

// Grey level 0..255 of value v on the display range [lo, hi] (report.hpp: clipped linear map,
// -inf black, +inf white), rounded to nearest.
std::uint8_t grey_level(double v, double lo, double hi);

// The plane as grey pixels, fitted into `area` keeping square pixels and centred horizontally
// (top-aligned), with a thin grey frame. Returns the box the image occupies.
Box draw_plane(cairo_t* cr, const Plane& values, double lo, double hi, const Box& area);

// A horizontal grey ramp in `bar` from black (lo) to white (hi), framed, with lo and hi printed
// under its ends (3 significant digits, then the unit).
void draw_colorbar(cairo_t* cr, const Box& bar, double lo, double hi, const std::string& unit,
                   const Font& font);

// A number for people: %.3g, "inf"/"-inf" for infinities.
std::string short_number(double v);

}  // namespace pinmask::report_draw
