#include "export/layout/vendor_rules.hpp"

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

// 16 um: the common film-plotter minimum for lines and spaces (about 12 pixels at 20 000 dpi).
constexpr std::int64_t kFilmMinNm = 16'000;
// 1 um: a conservative chrome-on-glass minimum for laser/e-beam written masks.
constexpr std::int64_t kChromeMinNm = 1'000;

std::vector<VendorRules> presets() {
    return {
        {"film", "laser film plotter, 20000 dpi: features and gaps >= 16 um", kFilmMinNm,
         kFilmMinNm, kGdsFriendlyMaxVertices},
        {"chrome", "chrome on glass: features and gaps >= 1 um", kChromeMinNm, kChromeMinNm,
         kGdsFriendlyMaxVertices},
        {"none", "no process limits (geometry rules only; polygons must not touch)", 0, 1,
         kGdsFriendlyMaxVertices},
    };
}

}  // namespace

std::vector<std::string> vendor_names() {
    std::vector<std::string> names;
    for (const auto& p : presets()) names.push_back(p.name);
    return names;
}

VendorRules vendor_rules(std::string_view name) {
    for (const auto& p : presets()) {
        if (p.name == name) return p;
    }
    std::string known;
    for (const auto& n : vendor_names()) known += (known.empty() ? "" : ", ") + n;
    throw invalid_field("vendor", std::string(name), "must be one of: " + known);
}

}  // namespace pinmask
