// PSF-synthesis flags shared by generate, search and simulate: the kernel model recorded in the
// mask and the image-plane cell pitch in pixels.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "design/camera.hpp"
#include "design/mask.hpp"

namespace pinmask::cli {

struct PsfOptions {
    std::string kernel = "auto";
    std::string kernel_path;
    std::optional<int> pixels_per_cell;
};

// --kernel, --kernel-path, --pixels-per-cell.
void add_psf_options(CLI::App& cmd, PsfOptions& o);

// The PsfSpec for these flags: pixels per cell as given, else the nearest integer to the pitch
// at the camera's object distance u (InvalidInput when that is below 1, naming the flag to set);
// kernel flags checked for consistency (measured needs --kernel-path and only it takes one).
PsfSpec resolve_psf_spec(const PsfOptions& o, const Camera& c);

}  // namespace pinmask::cli
