#include "export/formats/svg_writer.hpp"

#include "export/formats/decimal.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {
namespace {

constexpr int kMicrometreDigits = 3;  // nm -> um
constexpr int kMillimetreDigits = 6;  // nm -> mm

void append_group(std::string& out, const char* id, const std::vector<Ring>& rings,
                  const char* fill) {
    out += "<g id=\"";
    out += id;
    out += "\" fill=\"";
    out += fill;
    out += "\" stroke=\"none\">\n";
    for (const Ring& r : rings) {
        out += "<path d=\"";
        for (std::size_t i = 0; i < r.size(); ++i) {
            out.push_back(i == 0 ? 'M' : 'L');
            append_scaled(out, r[i].x, kMicrometreDigits);
            out.push_back(',');
            append_scaled(out, -r[i].y, kMicrometreDigits);
        }
        out += "Z\"/>\n";
    }
    out += "</g>\n";
}

}  // namespace

std::string svg_document(const Layout& layout, DrawMode draw) {
    const BoxNm& e = layout.extent;
    std::string out;
    std::size_t vertices = 0;
    for (const Ring& r : layout.polygons) vertices += r.size();
    out.reserve(512 + vertices * 24 + layout.polygons.size() * 16);
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
    // The film of a clear-tone layout: the extent opaque, the drawn (clear) rings white on it.
    const bool film = draw == DrawMode::kFilm && layout.tone == Tone::kClear;
    out += "<!-- pinmask fabrication drawing, scale 1:1. ";
    out += film ? "The film as it looks: black = opaque, white = clear; the white paths are the "
                  "drawn polygons, the clear"
                : "Black paths are the drawn polygons, the ";
    out += layout.tone == Tone::kClear ? (film ? "" : "clear (transparent)") : "opaque";
    out += " areas of the mask (tone ";
    out += tone_name(layout.tone);
    out += ", draw ";
    out += draw_mode_name(draw);
    out +=
        "). Units: viewBox in micrometres (1 user unit = 1 um), width and height in "
        "millimetres; y points down (y_svg = -y). Mirrored: ";
    out += layout.mirrored ? "yes (right-reading with the film side down)" : "no";
    out += ". -->\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"";
    append_scaled(out, e.x1 - e.x0, kMillimetreDigits);
    out += "mm\" height=\"";
    append_scaled(out, e.y1 - e.y0, kMillimetreDigits);
    out += "mm\" viewBox=\"";
    append_scaled(out, e.x0, kMicrometreDigits);
    out.push_back(' ');
    append_scaled(out, -e.y1, kMicrometreDigits);
    out.push_back(' ');
    append_scaled(out, e.x1 - e.x0, kMicrometreDigits);
    out.push_back(' ');
    append_scaled(out, e.y1 - e.y0, kMicrometreDigits);
    out += "\">\n<metadata>pinmask ";
    out += layout_info(layout, "um");
    out += " draw=";
    out += draw_mode_name(draw);
    out += "</metadata>\n";
    if (film) append_group(out, kSvgFilmGroup, {box_ring(e)}, "#000000");
    const char* fill = film ? "#ffffff" : "#000000";
    append_group(out, "pattern", layout.polygons, fill);
    append_group(out, "annotations", layout.annotations, fill);
    out += "</svg>\n";
    return out;
}

}  // namespace pinmask
