// What a fabrication file should be to be the film its export wrote (export/pipeline/film_identity
// FilmIdentityExpected), from the export sidecar beside it (the file's entry: GDSII/OASIS layer
// and datatype, DXF layer name; the tone: Gerber polarity) or, without a sidecar, from a vendor
// preset given to check (an export with a preset writes export's default layers, 1/0 and
// PINMASK, and the preset's tone) and a tone given to check. What neither says is not known, and
// the sources say why. Shared by `pinmask check` and the Python module's check().
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "export/pipeline/film_identity.hpp"
#include "io/export_sidecar.hpp"

namespace pinmask::io {

// `file`: the fabrication file checked; `side`: its sidecar (null: none read, `sidecar_path`
// names where it was looked for; `sidecar_ignored`: the user said to ignore it); `vendor`: the
// vendor name given to check (nullopt: none); `tone`: the tone given to check (nullopt: none).
// Throws InvalidInput for a vendor name that is neither a preset nor a rule name (as check's
// vendor rules do).
FilmIdentityExpected film_identity_expected(const std::filesystem::path& file,
                                            const ExportSidecar* side,
                                            const std::filesystem::path& sidecar_path,
                                            bool sidecar_ignored,
                                            const std::optional<std::string>& vendor,
                                            const std::optional<std::string>& tone);

}  // namespace pinmask::io
