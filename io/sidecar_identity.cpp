#include "io/sidecar_identity.hpp"

#include "core/errors/field_names.hpp"
#include "export/formats/read_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/pipeline/export_request.hpp"
#include "export/pipeline/vendor_presets.hpp"

namespace pinmask::io {

namespace fs = std::filesystem;

FilmIdentityExpected film_identity_expected(const fs::path& file, const ExportSidecar* side,
                                            const fs::path& sidecar_path, bool sidecar_ignored,
                                            const std::optional<std::string>& vendor,
                                            const std::optional<std::string>& tone) {
    FilmIdentityExpected e;
    const std::optional<FabFormat> format = readable_format_of(file);
    const std::string name = file.filename().string();
    if (side) {
        const std::string from = "the export sidecar " + sidecar_path.filename().string();
        e.tone = parse_tone(side->tone, "tone");
        e.tone_source = from;
        e.layer_source = from + ", which lists no layer for " + name;
        for (const ExportSidecarFile& f : side->files) {
            if (f.name != name) continue;
            if (f.detail.starts_with("layer ")) {
                e.layer = f.detail.substr(6);
                e.layer_source = from;
            }
        }
        return e;
    }
    const std::string name_of_sidecar = sidecar_path.filename().string();
    const std::string none = sidecar_ignored && fs::is_regular_file(sidecar_path)
                                 ? "the export sidecar " + name_of_sidecar + " ignored as asked"
                                 : "no export sidecar " + name_of_sidecar;
    const VendorPreset* preset = vendor ? find_vendor_preset(*vendor) : nullptr;
    if (preset) {
        const ExportRequest defaults;  // export's layers, which no preset changes
        e.layer = format == FabFormat::kDxf
                      ? defaults.dxf_layer
                      : std::to_string(defaults.layer) + "/" + std::to_string(defaults.datatype);
        e.layer_source =
            "export's default layer with the vendor preset " + preset->name + " (" + none + ")";
        e.tone = preset->tone;
        e.tone_source = "the vendor preset " + preset->name;
    } else {
        e.layer_source = none + " and no vendor preset given";
        e.tone_source = e.layer_source;
    }
    if (tone) {  // the tone given to check wins over the preset's, as export's flag does
        e.tone = parse_tone(*tone, field_ref("tone"));
        e.tone_source = "the tone given to check";
    }
    return e;
}

}  // namespace pinmask::io
