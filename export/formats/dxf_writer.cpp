#include "export/formats/dxf_writer.hpp"

#include <cctype>

#include "core/errors/error.hpp"
#include "export/formats/decimal.hpp"
#include "export/formats/fab_units.hpp"
#include "export/layout/geometry.hpp"

namespace pinmask {
namespace {

// Decimals written per unit: um and mm carry whole nanometres exactly (3 and 6 decimals); an
// inch is written in units of 1e-9 in (0.0254 nm), which reads back to the same nanometre.
int unit_digits(FabUnit unit) {
    return unit == FabUnit::kMicrometre ? 3 : unit == FabUnit::kMillimetre ? 6 : 9;
}

// nm -> count of 10^-digits drawing units (inches: rounded to the nearest 1e-9 in).
std::int64_t to_count(std::int64_t nm, FabUnit unit) {
    if (unit != FabUnit::kInch) return nm;
    // 1e-9 in = 0.0254 nm: count = nm / 0.0254 = nm * 10000 / 254, rounded half away from zero
    const std::int64_t num = nm * 10000;
    return num >= 0 ? (num + 127) / 254 : -((-num + 127) / 254);
}

class Dxf {
  public:
    Dxf(std::string& out, FabUnit unit) : out_(out), unit_(unit) {}
    void group(int code, std::string_view value) {
        code_(code);
        out_ += value;
        out_.push_back('\n');
    }
    void coord(int code, std::int64_t nm) {
        code_(code);
        append_scaled(out_, to_count(nm, unit_), unit_digits(unit_));
        out_.push_back('\n');
    }

  private:
    void code_(int code) {  // right-aligned in three columns, as AutoCAD writes them
        if (code < 100) out_.push_back(' ');
        if (code < 10) out_.push_back(' ');
        out_ += std::to_string(code);
        out_.push_back('\n');
    }
    std::string& out_;
    FabUnit unit_;
};

void check_layer(const std::string& name) {
    bool ok = !name.empty() && name.size() <= 31 && name != "0";
    for (char c : name)
        ok =
            ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '$');
    if (!ok)
        throw invalid_field("dxf layer", "'" + name + "'",
                            "must be 1..31 characters of A-Z a-z 0-9 _ - $ and not \"0\"");
}

}  // namespace

std::string dxf_document(const Layout& layout, const DxfOptions& o) {
    check_layer(o.layer);
    std::string out;
    std::size_t vertices = 0;
    for (const Ring& r : layout.polygons) vertices += r.size();
    out.reserve(1024 + vertices * 60 + layout.polygons.size() * 80);
    Dxf d(out, o.unit);
    const std::string unit = fab_unit_name(o.unit);
    d.group(999, "pinmask fabrication drawing, scale 1:1, units " + fab_unit_words(o.unit) +
                     " (1 drawing unit = 1 " + unit + ")");
    d.group(999, std::string("closed polylines are the ") +
                     (layout.tone == Tone::kClear ? "clear (transparent)" : "opaque") +
                     " areas of the mask");
    d.group(999, "pinmask " + layout_info(layout, unit));
    d.group(0, "SECTION");
    d.group(2, "HEADER");
    d.group(9, "$ACADVER");
    d.group(1, "AC1009");
    d.group(9, "$INSUNITS");
    d.group(70, std::to_string(dxf_insunits(o.unit)));
    d.group(9, "$MEASUREMENT");
    d.group(70, o.unit == FabUnit::kInch ? "0" : "1");
    d.group(9, "$EXTMIN");
    d.coord(10, layout.extent.x0);
    d.coord(20, layout.extent.y0);
    d.group(9, "$EXTMAX");
    d.coord(10, layout.extent.x1);
    d.coord(20, layout.extent.y1);
    d.group(0, "ENDSEC");
    d.group(0, "SECTION");
    d.group(2, "TABLES");
    d.group(0, "TABLE");
    d.group(2, "LTYPE");
    d.group(70, "1");
    d.group(0, "LTYPE");
    d.group(2, "CONTINUOUS");
    d.group(70, "0");
    d.group(3, "Solid line");
    d.group(72, "65");
    d.group(73, "0");
    d.group(40, "0.0");
    d.group(0, "ENDTAB");
    d.group(0, "TABLE");
    d.group(2, "LAYER");
    d.group(70, "1");
    d.group(0, "LAYER");
    d.group(2, o.layer);
    d.group(70, "0");
    d.group(62, "7");
    d.group(6, "CONTINUOUS");
    d.group(0, "ENDTAB");
    d.group(0, "ENDSEC");
    d.group(0, "SECTION");
    d.group(2, "ENTITIES");
    const bool circles = o.native_circles && !layout.circles.empty();
    for (const CircleNm& c : circles ? layout.circles : std::vector<CircleNm>{}) {
        d.group(0, "CIRCLE");
        d.group(8, o.layer);
        d.coord(10, c.centre.x);
        d.coord(20, c.centre.y);
        d.group(30, "0.0");
        d.coord(40, c.diameter_nm / 2);
    }
    for (const auto* set : {circles ? nullptr : &layout.polygons, &layout.annotations})
        for (const Ring& r : set ? *set : std::vector<Ring>{}) {
            d.group(0, "POLYLINE");
            d.group(8, o.layer);
            d.group(66, "1");
            d.group(10, "0.0");
            d.group(20, "0.0");
            d.group(30, "0.0");
            d.group(70, "1");
            for (const PointNm& p : r) {
                d.group(0, "VERTEX");
                d.group(8, o.layer);
                d.coord(10, p.x);
                d.coord(20, p.y);
                d.group(30, "0.0");
            }
            d.group(0, "SEQEND");
            d.group(8, o.layer);
        }
    d.group(0, "ENDSEC");
    d.group(0, "EOF");
    return out;
}

}  // namespace pinmask
