#include "export/formats/klayout_open.hpp"

#include <cstdio>

namespace pinmask {

double klayout_dxf_unit_um(FabUnit unit) { return double(nm_per_unit(unit)) * 1e-3; }

std::string klayout_open_text(FabFormat format, FabUnit unit) {
    const std::string u = fab_unit_name(unit);
    switch (format) {
        case FabFormat::kGds:
        case FabFormat::kOasis:
            return "database unit 1 nm, user unit 1 " + u +
                   ": KLayout opens it at scale (File > Open)";
        case FabFormat::kDxf: {
            char um[32];
            std::snprintf(um, sizeof um, "%g", klayout_dxf_unit_um(unit));
            return "drawn in " + fab_unit_words(unit) + " ($INSUNITS " +
                   std::to_string(dxf_insunits(unit)) +
                   "); KLayout ignores $INSUNITS and reads micrometres: open it with File > "
                   "Reader Options > DXF > DXF unit = " +
                   std::string(um) +
                   " (um per drawing unit; in a script LoadLayoutOptions."
                   "dxf_unit = " +
                   std::string(um) + ")";
        }
        case FabFormat::kGerber:
            return "drawn in millimetres (%MOMM*%): KLayout opens it at scale with File > "
                   "Import > Gerber PCB";
        case FabFormat::kSvg:
            return "viewBox in micrometres, page size in millimetres: not a KLayout format "
                   "(a browser or Inkscape shows it at scale)";
        case FabFormat::kPdf:
            return "points (1/72 in) at scale 1:1: not a KLayout format (print at 100 %)";
        case FabFormat::kPng:
            return "a preview in pixels: not a KLayout format, not to scale";
        case FabFormat::kTiff1:
            return "pixels at the plotter's dpi (resolution tags in inches): not a KLayout "
                   "format (the plotter's RIP reads the dpi)";
    }
    return "";
}

}  // namespace pinmask
