#include "cli/check_settings.hpp"

#include "core/units.hpp"
#include "io/sidecar_layout.hpp"

namespace pinmask::cli {

namespace fs = std::filesystem;

// The flags as given settings; the rules are io/sidecar_layout's (shared with the Python module).
LayoutOptions design_options(const CheckOptions& o, const io::ExportSidecar* side) {
    io::CheckLayoutSettings g;
    g.shape = o.shape;
    g.sides = o.sides;
    const auto length = [](const std::optional<std::string>& v,
                           const char* flag) -> std::optional<io::GivenLength> {
        if (!v) return std::nullopt;
        return io::GivenLength{parse_length_m(*v, flag), *v};
    };
    g.hole_side = length(o.hole_side, "--hole-side");
    g.frame = length(o.frame, "--frame");
    g.chord_tol = length(o.chord_tol, "--chord-tol");
    g.tone = o.tone;
    g.units = o.units;
    g.mirror = o.mirror;
    return io::check_layout(g, side);
}

std::string sidecar_mask(const io::ExportSidecar& side, const fs::path& sidecar) {
    return io::sidecar_mask(side, sidecar);
}
}  // namespace pinmask::cli
