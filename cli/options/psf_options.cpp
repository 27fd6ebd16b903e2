#include "cli/options/psf_options.hpp"

#include "design/psf/kernel_model.hpp"

namespace pinmask::cli {

void add_psf_options(CLI::App& cmd, PsfOptions& o) {
    cmd.add_option("--kernel", o.kernel,
                   "Single-pinhole kernel model for PSF synthesis: " + kernel_model_names() +
                       " (auto picks by Fresnel number and says which)")
        ->check(CLI::IsMember(name_list(kKernelModelNames)))
        ->capture_default_str();
    cmd.add_option("--kernel-path", o.kernel_path, "Kernel image for --kernel measured");
    cmd.add_option("--pixels-per-cell", o.pixels_per_cell,
                   "Image-plane cell pitch in sensor pixels (integer >= 1). Default: the nearest "
                   "integer to d |1 - f/f' + f/u| / w, the pitch at the object distance u "
                   "(paper: 8.08 at 6 m -> 8)");
}

}  // namespace pinmask::cli
