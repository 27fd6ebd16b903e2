#include "export/formats/gerber_writer.hpp"

#include <algorithm>

#include "core/errors/error.hpp"
#include "core/version.hpp"
#include "export/formats/decimal.hpp"
#include "export/layout/geometry.hpp"

namespace pinmask {
namespace {

constexpr std::int64_t kMaxFormatNm = 9'999'999'999;  // 9999.999999 mm in format 4.6

void append_point(std::string& out, const PointNm& p, const char* op) {
    if (p.x > kMaxFormatNm || p.x < -kMaxFormatNm || p.y > kMaxFormatNm || p.y < -kMaxFormatNm)
        throw invalid_field("gerber coordinate", std::to_string(p.x) + ", " + std::to_string(p.y),
                            "outside the 4.6 millimetre format");
    out.push_back('X');
    out += std::to_string(p.x);
    out.push_back('Y');
    out += std::to_string(p.y);
    out += op;
}

}  // namespace

std::string gerber_file_polarity(Tone tone) {
    return tone == Tone::kClear ? "Negative" : "Positive";
}

std::string gerber_document(const Layout& layout, bool native_circles) {
    const bool clear = layout.tone == Tone::kClear;
    std::string out;
    std::size_t vertices = 0;
    for (const Ring& r : layout.polygons) vertices += r.size() + 1;
    out.reserve(1024 + vertices * 24 + layout.polygons.size() * 12);
    out += "G04 pinmask fabrication image, scale 1:1, units mm (format 4.6: integers are nm)*\n";
    out += "G04 pinmask " + layout_info(layout, "mm") + "*\n";
    out += clear ? "G04 Regions are the clear (transparent) areas: file polarity Negative*\n"
                 : "G04 Regions are the opaque (chrome) areas: file polarity Positive*\n";
    out += "%TF.GenerationSoftware,pinmask,pinmask," PINMASK_VERSION "*%\n";
    out += "%TF.FileFunction,Other,Photomask*%\n";
    out += "%TF.FilePolarity," + gerber_file_polarity(layout.tone) + "*%\n";
    out += "%FSLAX46Y46*%\n";
    out += "%MOMM*%\n";
    out += "%LPD*%\n";
    const bool circles = native_circles && !layout.circles.empty();
    if (circles) {
        // One aperture per diameter (all pinholes share one), then a flash per pinhole.
        std::vector<std::int64_t> diameters;
        for (const CircleNm& c : layout.circles)
            if (std::find(diameters.begin(), diameters.end(), c.diameter_nm) == diameters.end())
                diameters.push_back(c.diameter_nm);
        for (std::size_t k = 0; k < diameters.size(); ++k) {
            out += "%ADD" + std::to_string(10 + k) + "C,";
            append_scaled(out, diameters[k], 6);
            out += "*%\n";
        }
        std::int64_t current = -1;
        for (const CircleNm& c : layout.circles) {
            if (c.diameter_nm != current) {
                const auto k = std::find(diameters.begin(), diameters.end(), c.diameter_nm) -
                               diameters.begin();
                out += "D" + std::to_string(10 + k) + "*\n";
                current = c.diameter_nm;
            }
            append_point(out, c.centre, "D03*\n");
        }
    }
    out += "G01*\n";
    for (const auto* set : {circles ? nullptr : &layout.polygons, &layout.annotations})
        for (const Ring& r : set ? *set : std::vector<Ring>{}) {
            out += "G36*\n";
            append_point(out, r.front(), "D02*\n");
            for (std::size_t i = 1; i < r.size(); ++i) append_point(out, r[i], "D01*\n");
            append_point(out, r.front(), "D01*\n");
            out += "G37*\n";
        }
    out += "M02*\n";
    return out;
}

}  // namespace pinmask
