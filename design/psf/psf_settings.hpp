// The PSF settings a user gives (kernel model, measured kernel file, image-plane cell pitch in
// pixels) and the PsfSpec they resolve to for a camera. Shared by generate, search, simulate and
// the Python module; errors name the fields below (field_ref), which each face spells.
#pragma once

#include <optional>
#include <string>

#include "design/optics/camera.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask {

struct PsfSettings {
    std::string kernel = "auto";  // auto | box | fraunhofer | fresnel | paper-fig3b | measured
    std::string kernel_path;      // the kernel image, only with kernel "measured"
    std::optional<int> pixels_per_cell;  // >= 1; empty: from the camera (below)
};

// The PsfSpec for these settings: pixels per cell as given, else the nearest integer to the pitch
// d |1 - f/f' + f/u| / w at the camera's object distance u (InvalidInput when that is below 1,
// naming pixels_per_cell); kernel settings checked for consistency (measured needs
// kernel_path and only it takes one).
PsfSpec resolve_psf_spec(const PsfSettings& o, const Camera& c);

// The kernel settings' consistency: kernel "measured" needs a kernel_path and only it takes one
// (InvalidInput naming the field otherwise). An empty kernel means "not given" (the mask's own
// model): then no path may be given either. With "measured", the path must name a regular file
// (core/files/input_file). The model name itself is the caller's to check.
void check_kernel_settings(const std::string& kernel, const std::string& kernel_path);

}  // namespace pinmask
