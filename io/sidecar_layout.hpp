// The layout settings of a design that a fabrication file is checked against, from the export
// sidecar beside the file (NAME.export.json, io/export_sidecar.hpp) and the settings a user
// gives (as `pinmask check` flags: each must agree with the sidecar), or from the given settings
// and what the file declares when there is no sidecar. Used by `pinmask check` (its flags) and
// the Python module's check() (its arguments); errors name the settings' fields
// (core/errors/field_names.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/vendor_rules.hpp"
#include "io/export_sidecar.hpp"

namespace pinmask::io {

// A length as given: metres and the text (for messages).
struct GivenLength {
    double m = 0.0;
    std::string text;
};

// The layout settings a user gives; an empty field is not given.
struct CheckLayoutSettings {
    std::optional<std::string> shape;  // square | circle | polygon
    std::optional<int> sides;          // polygon sides, >= 3
    std::optional<GivenLength> hole_side, frame, chord_tol;
    std::optional<std::string> tone;   // clear | dark (and aliases)
    std::optional<std::string> units;  // um | mm | in, checked against the sidecar only
    bool mirror = false;
};

// The layout settings as a user gives them (`pinmask check` flags, the Python check()
// arguments): text as typed; an empty field is not given.
struct CheckLayoutText {
    std::optional<std::string> shape;
    std::optional<int> sides;
    std::optional<std::string> hole_side, frame, chord_tol;  // lengths: with a unit, or metres
    std::optional<std::string> tone, units;
    bool mirror = false;
};

// The settings from their text (lengths parsed here; InvalidInput naming the field).
CheckLayoutSettings check_layout_settings(const CheckLayoutText& given);

// The sidecar's layout settings, every given setting required to agree with it (InvalidInput
// naming the field otherwise); without a sidecar, the given settings over the defaults.
LayoutOptions check_layout(const CheckLayoutSettings& given, const ExportSidecar* side);

// Tone, mirroring and grid as a fabrication file declares them (its info), over `lo`: the
// design's settings when no sidecar gives them.
void apply_file_declarations(LayoutOptions& lo, const FileGeometry& file);

// The design rules the export checked, as its sidecar records them (an older sidecar without
// them: its vendor's rule preset, export/pipeline/vendor_presets vendor_rules_for).
VendorRules sidecar_rules(const ExportSidecar& side);

// InvalidInput when the file's declared unit disagrees with the sidecar's.
void check_sidecar_unit(const ExportSidecar& side, const FileGeometry& file);

// The mask a sidecar names: its recorded path, else relative to the sidecar's folder; "" when
// none exists.
std::string sidecar_mask(const ExportSidecar& side, const std::filesystem::path& sidecar);

}  // namespace pinmask::io
