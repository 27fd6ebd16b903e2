#include "export/pipeline/vendor_presets.hpp"

#include <cstdio>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/vendor_rules.hpp"

namespace pinmask {
namespace {

constexpr double kInch = 25.4e-3;
// A 5-inch plate (127 mm) with a 10 mm handling border on each side: 107 mm of quality area.
constexpr double kFiveInchQualityArea = 5 * kInch - 2 * 10e-3;

std::vector<VendorPreset> make_presets() {
    using F = FabFormat;
    std::vector<VendorPreset> v;
    v.push_back({.name = "chrome-photomask",
                 .description =
                     "chrome-on-glass photomask shop: GDSII + OASIS, um, dark field "
                     "(drawn polygons are the clear pinholes in chrome), chrome side up, "
                     "1 mm frame, 1 nm grid, extent within a 5-inch plate's 107 mm",
                 .formats = {F::kGds, F::kOasis},
                 .unit = FabUnit::kMicrometre,
                 .tone = Tone::kClear,
                 .frame_m = 1e-3,
                 .plate_m = kFiveInchQualityArea,
                 .drc = "chrome"});
    v.push_back({.name = "film-plotter",
                 .description = "laser film plotter: DXF R12 in mm + 1-bit TIFF at 25400 dpi, "
                                "negative (clear pinholes), emulsion down, 2 mm frame, 1 um grid",
                 .formats = {F::kDxf, F::kTiff1},
                 .unit = FabUnit::kMillimetre,
                 .tone = Tone::kClear,
                 .emulsion_down = true,
                 .frame_m = 2e-3,
                 .grid_m = 1e-6,
                 .tiff_dpi = 25400,
                 .drc = "film"});
    v.push_back({.name = "gerber-film",
                 .description = "PCB-film / photoplotter shop: Gerber X2 in mm, negative, emulsion "
                                "down, round pinholes as circular flashes, 2 mm frame, 1 um grid",
                 .formats = {F::kGerber},
                 .unit = FabUnit::kMillimetre,
                 .tone = Tone::kClear,
                 .emulsion_down = true,
                 .frame_m = 2e-3,
                 .grid_m = 1e-6,
                 .native_circles = true,
                 .drc = "film"});
    v.push_back({.name = "laser-cutter",
                 .description = "laser cutter (metal foil): DXF in mm, cut outlines are the holes, "
                                "kerf 20 um compensated (" +
                                field_ref("kerf_m") +
                                "), round holes as CIRCLE entities, 1 um grid",
                 .formats = {F::kDxf},
                 .unit = FabUnit::kMillimetre,
                 .tone = Tone::kClear,
                 .grid_m = 1e-6,
                 .native_circles = true,
                 .kerf_m = 20e-6,
                 .drc = "film"});
    return v;
}

}  // namespace

const std::vector<VendorPreset>& vendor_presets() {
    static const std::vector<VendorPreset> presets = make_presets();
    return presets;
}

const VendorPreset* find_vendor_preset(std::string_view name) {
    for (const VendorPreset& p : vendor_presets())
        if (p.name == name) return &p;
    for (const std::string& n : vendor_names())
        if (n == name) return nullptr;
    std::string known;
    for (const VendorPreset& p : vendor_presets()) known += p.name + ", ";
    for (const std::string& n : vendor_names()) known += n + ", ";
    throw invalid_field(field_ref("vendor"), std::string(name),
                        "must be list or one of: " + known.substr(0, known.size() - 2));
}

VendorRules vendor_rules_for(std::string_view name) {
    const VendorPreset* p = find_vendor_preset(name);
    return vendor_rules(p ? std::string_view(p->drc) : name);
}

std::string vendor_rules_text(const VendorRules& r) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "features >= %.3f um, spaces >= %.3f um, <= %zu vertices",
                  double(r.min_feature_nm) * 1e-3, double(r.min_gap_nm) * 1e-3, r.max_vertices);
    return buf;
}

std::string vendor_list_text() {
    std::string s = "Vendor presets (explicit flags win over a preset):\n";
    for (const VendorPreset& p : vendor_presets()) {
        std::string formats;
        for (FabFormat f : p.formats) {
            if (!formats.empty()) formats.push_back(',');
            formats.append(fab_format_name(f));
        }
        char buf[160];
        std::snprintf(buf, sizeof buf, "    formats %s, units %s, tone %s, emulsion %s, rules %s\n",
                      formats.c_str(), fab_unit_name(p.unit).c_str(), tone_name(p.tone).c_str(),
                      p.emulsion_down ? "down" : "up", p.drc.c_str());
        s.append("  ").append(p.name).append(": ").append(p.description).append("\n").append(buf);
    }
    s += "Design-rule presets (set only the rules of the check):\n";
    for (const std::string& n : vendor_names())
        s.append("  ").append(n).append(": ").append(vendor_rules(n).description).append("\n");
    return s;
}

}  // namespace pinmask
