#include "cli/outputs/check_picture.hpp"

#include <filesystem>
#include <optional>

#include "core/errors/error.hpp"
#include "io/export_sidecar.hpp"
#include "io/mask_json.hpp"
#include "io/sidecar_layout.hpp"

namespace pinmask::cli {

FileCheck check_picture(const CheckOptions& o, const VendorRules& vendor, CheckReport& rep) {
    namespace fs = std::filesystem;
    const fs::path side_path = io::sidecar_path_for(o.input);
    std::optional<io::ExportSidecar> side;
    if (!o.no_sidecar && fs::is_regular_file(side_path)) side = io::read_export_sidecar(side_path);
    if (side) {
        rep.settings = "from " + side_path.string();
        if (rep.mask.empty()) rep.mask = io::sidecar_mask(*side, side_path);
    } else {
        rep.settings = "from the flags (no sidecar " + side_path.filename().string() + ")";
    }
    if (rep.mask.empty())
        throw invalid_field("--mask", "''",
                            "a PDF, PNG or TIFF is compared with its design: keep the export "
                            "sidecar (and its mask) beside the file, or give --mask");
    const Mask mask = io::read_mask_file(rep.mask, {.allow_spacing_violations = true});
    const Layout design = make_layout(mask, design_options(o, side ? &*side : nullptr));
    rep.rules = resolve_rules(o, rules_for_mask(mask, vendor, design.grid_nm));
    PictureCheckOptions po;
    po.rules = rep.rules;
    if (side) {
        po.draw = parse_draw_mode(side->draw, "sidecar geometry.draw");
        po.png_dpi = side->png_dpi;
        po.pdf.margin_m = side->pdf_margin_m;
    }
    rep.note =
        "the design (rebuilt from the mask) is design-rule checked; the picture is "
        "compared with it";
    return check_picture_file(o.input, design, po);
}

}  // namespace pinmask::cli
