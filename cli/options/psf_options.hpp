// PSF-synthesis flags shared by generate, search and simulate: the kernel model recorded in the
// mask and the image-plane cell pitch in pixels.
#pragma once

#include <CLI/CLI.hpp>

#include "design/psf/psf_settings.hpp"

namespace pinmask::cli {

// The settings as parsed (design/psf/psf_settings.hpp).
using PsfOptions = PsfSettings;

// --kernel, --kernel-path, --pixels-per-cell.
void add_psf_options(CLI::App& cmd, PsfOptions& o);

using pinmask::resolve_psf_spec;

}  // namespace pinmask::cli
