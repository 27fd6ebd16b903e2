#include "cli/check_settings.hpp"

#include "io/sidecar_layout.hpp"

namespace pinmask::cli {

namespace fs = std::filesystem;

// The flags as given settings; the rules are io/sidecar_layout's (shared with the Python module).
LayoutOptions design_options(const CheckOptions& o, const io::ExportSidecar* side) {
    return io::check_layout(io::check_layout_settings(o.shape, o.sides, o.hole_side, o.frame,
                                                      o.chord_tol, o.tone, o.units, o.mirror),
                            side);
}

std::string sidecar_mask(const io::ExportSidecar& side, const fs::path& sidecar) {
    return io::sidecar_mask(side, sidecar);
}
}  // namespace pinmask::cli
