// The `*.mask.json` codec (docs/design.md section 5): the only place mask files are parsed or written.
// Reading validates everything: JSON syntax, "format" == "pinmask-mask", "version" == 1, known
// keys only (an unknown key is an error naming it), types, camera physics (design/optics/camera),
// the pattern structure and its spacing rule (design/pattern/pattern) unless the file records that
// violations were allowed. Every failure is InvalidInput naming the file, the key and the rule.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "design/pattern/mask.hpp"

namespace pinmask::io {

struct MaskReadOptions {
    // Accept spacing violations even when the file does not record that they were allowed.
    bool allow_spacing_violations = false;
};

Mask mask_from_json(const nlohmann::json& j, const MaskReadOptions& options = {});
nlohmann::json mask_to_json(const Mask& mask);

// The exact bytes write_mask_file writes (validated by reading them back first).
std::string mask_file_text(const Mask& mask);

Mask read_mask_file(const std::filesystem::path& path, const MaskReadOptions& options = {});

// True when `path` names a mask file rather than a fabrication file: a .json name, or JSON by its
// first non-blank byte '{' (pinmask check and the Python check() tell their input kinds apart so).
bool is_mask_file(const std::filesystem::path& path);

// Atomic write, pretty-printed with 2-space indent, keys in a fixed order; byte-identical for
// identical masks.
void write_mask_file(const std::filesystem::path& path, const Mask& mask);

}  // namespace pinmask::io
